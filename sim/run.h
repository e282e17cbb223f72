#pragma once
// `polysim run`: a whole simulation and its summary (SPEC.md).

#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "collision/time_of_contact.h"
#include "sim/scene.h"

namespace polysim::sim {

/// The most steps one run takes (`checkRunLength`): 10^8 steps is a day at 1 ms a step
/// and a step log of tens of GB; a longer run is almost surely a mistyped duration or dt.
inline constexpr long kMaxRunSteps = 100'000'000;

struct RunOptions {
  std::optional<double> duration, dt;  // s; the scene's when not given
  std::string logPath;                 // empty: no step log
  bool logContacts = false;            // the step log holds each step's contacts (step_log.h)
  std::string logDirectory;            // compare: both engines' step logs go here (polysim.jsonl, ode.jsonl)
  collision::TocMethod method = collision::TocMethod::Bisection;
  bool progress = false;               // a progress bar on stderr

  double dtFor(const Scene& scene) const { return dt.value_or(scene.dt); }
  long stepsFor(const Scene& scene) const { return std::lround(duration.value_or(scene.duration) / dtFor(scene)); }
};

/// Throws std::invalid_argument naming the option at fault (--dt, --duration) unless dt
/// and duration are finite and positive and make from 1 to kMaxRunSteps steps.
void checkRunLength(const Scene& scene, const RunOptions& options);

/// Runs the scene and returns SPEC.md's summary: scene, steps, sim_time, wall_time_s,
/// first_contact_time, max_penetration, energy {initial, final, max_increase}, bodies
/// (dynamic ones: pose, velocities, at_rest); plus event_limit_steps, the steps that hit
/// kMaxEventsPerStep, and islands_joined, the times an event turned a body towards
/// another island's and the two went on as one (StepReport::islandsJoined).
nlohmann::ordered_json runScene(const Scene& scene, const RunOptions& options);

}  // namespace polysim::sim
