#include "sim/run.h"

#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>

#include "sim/json_output.h"
#include "sim/step_log.h"
#include "sim/world.h"

namespace polysim::sim {
namespace {

// Redraws "[#####     ] 50%" on stderr when the percentage changes.
class ProgressBar {
 public:
  explicit ProgressBar(long total) : total_(total) {}
  void update(long done) {
    const int percent = static_cast<int>(100 * done / total_);
    if (percent == shown_) return;
    shown_ = percent;
    std::cerr << "\r[" << std::string(percent / 5, '#') << std::string(20 - percent / 5, ' ') << "] " << percent << "%"
              << std::flush;
    if (done == total_) std::cerr << "\n";
  }

 private:
  long total_;
  int shown_ = -1;
};

}  // namespace

nlohmann::ordered_json runScene(const Scene& scene, const RunOptions& options) {
  const double dt = options.dt.value_or(scene.dt);
  const double duration = options.duration.value_or(scene.duration);
  const long steps = std::lround(duration / dt);
  World world(scene, options.method);
  std::unique_ptr<StepLog> log;
  if (!options.logPath.empty()) log = std::make_unique<StepLog>(options.logPath);
  std::unique_ptr<ProgressBar> bar;
  if (options.progress) bar = std::make_unique<ProgressBar>(steps);

  const double initialEnergy = world.energy();
  double maxIncrease = 0.0, maxPenetration = 0.0;
  long eventLimitSteps = 0;
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) {
    const StepReport& report = world.step(dt);
    maxIncrease = std::max(maxIncrease, world.energy() - initialEnergy);
    maxPenetration = std::max(maxPenetration, report.penetration);
    eventLimitSteps += report.eventLimitHit;
    if (log) log->write(world, report);
    if (bar) bar->update(k + 1);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (size_t i = 0; i < world.bodies().size(); ++i) {
    const dynamics::RigidBody& b = world.bodies()[i];
    if (b.isStatic) continue;
    nlohmann::ordered_json state =
        bodyStateToJson(scene.bodies[i].name, b.position, b.orientation, b.velocity, b.angularVelocity);
    state["at_rest"] = world.atRest(static_cast<int>(i));
    bodies.push_back(state);
  }
  nlohmann::ordered_json summary;
  summary["scene"] = scene.name;
  summary["steps"] = steps;
  summary["sim_time"] = forOutput(world.time());
  summary["wall_time_s"] = wall;
  summary["first_contact_time"] =
      world.firstContactTime() < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(forOutput(world.firstContactTime()));
  summary["max_penetration"] = forOutput(maxPenetration);
  summary["energy"] = {{"initial", forOutput(initialEnergy)},
                       {"final", forOutput(world.energy())},
                       {"max_increase", forOutput(maxIncrease)}};
  summary["bodies"] = bodies;
  summary["event_limit_steps"] = eventLimitSteps;
  return summary;
}

}  // namespace polysim::sim
