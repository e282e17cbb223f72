#pragma once
// A whole run of either engine, measured the same way: what SPEC.md's summary prints and
// what the sweep scores against analytic answers.

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "sim/engine.h"

namespace polysim::sim {

struct RunRecord {
  long steps = 0;
  double simTime = 0.0;   // s
  double wallTime = 0.0;  // s, stepping only (building the scene is not counted)
  /// s, the stepping thread's CPU time over the same span: unlike the wall time it does
  /// not grow when other runs share the machine's cores (the sweep's cost figure).
  double cpuTime = 0.0;
  std::optional<double> firstContactTime;  // s
  double maxPenetration = 0.0;             // m, deepest overlap in any step
  double initialEnergy = 0.0, finalEnergy = 0.0, maxEnergyIncrease = 0.0;  // J
  std::vector<BodyState> initial, final;   // dynamic bodies, scene order
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  // heights are measured along it (Scene::up)
  /// Per dynamic body: the highest its origin rose along `up` (m) after the first
  /// contact, sampled at step ends; the apex of its first rebound. NaN with no contact.
  std::vector<double> apexAfterFirstContact;
  /// s: the end of the last step at which some dynamic body was not at rest
  /// (dynamics::atRest, kRestSpeed), when every body is at rest at the run's end (0 when
  /// none ever moved); none when some body still moves at the end.
  std::optional<double> timeToRest;

  /// How far dynamic body i's origin ended from where it started, across `up` (m).
  double drift(size_t i) const;
  /// How far it ended above (> 0) or below where it started, along `up` (m).
  double heightChange(size_t i) const { return (final[i].position - initial[i].position).dot(up); }
};

/// CPU time (s) used so far by the whole process, every thread of it: the contact solver
/// sweeps on a second thread (dynamics/work_sharing.h), and that work is the run's too.
/// Wall time would also count other processes.
double processCpuSeconds();

/// Steps `engine` `steps` times by dt, calling afterStep (when given) after each step.
/// `up` is the scene's (Scene::up).
RunRecord recordRun(Engine& engine, long steps, double dt, const Eigen::Vector3d& up,
                    const std::function<void()>& afterStep = {});

/// SPEC.md's summary of a run: scene, steps, sim_time, wall_time_s, first_contact_time,
/// max_penetration, energy, bodies.
nlohmann::ordered_json summaryToJson(const std::string& sceneName, const RunRecord& record);

}  // namespace polysim::sim
