#include "sim/run_record.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>

#include "sim/json_output.h"

namespace polysim::sim {

double processCpuSeconds() {
  constexpr double kSecondsPerNanosecond = 1e-9;
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + kSecondsPerNanosecond * static_cast<double>(t.tv_nsec);
}

double RunRecord::drift(size_t i) const {
  const Eigen::Vector3d moved = final[i].position - initial[i].position;
  return (moved - moved.dot(up) * up).norm();
}

RunRecord recordRun(Engine& engine, long steps, double dt, const Eigen::Vector3d& up,
                    const std::function<void()>& afterStep) {
  RunRecord r;
  r.steps = steps;
  r.up = up;
  r.initial = engine.bodyStates();
  r.initialEnergy = engine.energy();
  r.apexAfterFirstContact.assign(r.initial.size(), std::numeric_limits<double>::quiet_NaN());
  const auto start = std::chrono::steady_clock::now();
  const double cpuStart = processCpuSeconds();
  double lastMoving = 0.0;  // s
  bool allAtRest = std::all_of(r.initial.begin(), r.initial.end(), [](const BodyState& b) { return b.atRest; });
  for (long k = 0; k < steps; ++k) {
    engine.step(dt);
    r.maxEnergyIncrease = std::max(r.maxEnergyIncrease, engine.energy() - r.initialEnergy);
    r.maxPenetration = std::max(r.maxPenetration, engine.stepPenetration());
    const std::vector<BodyState> states = engine.bodyStates();
    allAtRest = std::all_of(states.begin(), states.end(), [](const BodyState& b) { return b.atRest; });
    if (!allAtRest) lastMoving = static_cast<double>(k + 1) * dt;
    if (engine.firstContactTime()) {
      for (size_t i = 0; i < states.size(); ++i) {
        const double height = states[i].position.dot(up);
        if (!(r.apexAfterFirstContact[i] >= height)) r.apexAfterFirstContact[i] = height;  // NaN-aware max
      }
    }
    if (afterStep) afterStep();
  }
  if (allAtRest) r.timeToRest = lastMoving;
  r.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.cpuTime = processCpuSeconds() - cpuStart;
  r.simTime = steps * dt;
  r.firstContactTime = engine.firstContactTime();
  r.finalEnergy = engine.energy();
  r.final = engine.bodyStates();
  return r;
}

nlohmann::ordered_json summaryToJson(const std::string& sceneName, const RunRecord& r) {
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (const BodyState& b : r.final) {
    nlohmann::ordered_json state = bodyStateToJson(b.name, b.position, b.orientation, b.velocity, b.angularVelocity);
    state["at_rest"] = b.atRest;
    bodies.push_back(state);
  }
  nlohmann::ordered_json summary;
  summary["scene"] = sceneName;
  summary["steps"] = r.steps;
  summary["sim_time"] = forOutput(r.simTime);
  summary["wall_time_s"] = r.wallTime;
  summary["cpu_time_s"] = r.cpuTime;
  summary["first_contact_time"] =
      r.firstContactTime ? nlohmann::ordered_json(forOutput(*r.firstContactTime)) : nlohmann::ordered_json(nullptr);
  summary["max_penetration"] = forOutput(r.maxPenetration);
  summary["energy"] = {{"initial", forOutput(r.initialEnergy)},
                       {"final", forOutput(r.finalEnergy)},
                       {"max_increase", forOutput(r.maxEnergyIncrease)}};
  summary["time_to_rest"] = r.timeToRest ? nlohmann::ordered_json(forOutput(*r.timeToRest)) : nlohmann::ordered_json(nullptr);
  summary["bodies"] = bodies;
  return summary;
}

}  // namespace polysim::sim
