#include "sim/run.h"

#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "sim/polysim_engine.h"
#include "sim/run_record.h"
#include "sim/step_log.h"

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

// A state or energy that overflowed (a density of 1e308, a speed of 1e308) is an error
// naming the body and the time, not a summary of nulls; the step log keeps every step
// before it.
void checkFinite(const Scene& scene, const World& world) {
  for (size_t i = 0; i < world.bodies().size(); ++i) {
    const dynamics::RigidBody& b = world.bodies()[i];
    const double energy = b.kineticEnergy() - b.mass * scene.gravity.dot(b.centerOfMass());  // J, as World::energy
    if (b.isStatic || (b.position.allFinite() && b.velocity.allFinite() && b.angularVelocity.allFinite() &&
                       b.orientation.coeffs().allFinite() && std::isfinite(energy)))
      continue;
    std::ostringstream s;
    s << scene.file << ": body \"" << scene.bodies[i].name << "\": its state overflowed at t = " << world.time()
      << " s (a mass, density or speed beyond what double precision can simulate)";
    throw std::runtime_error(s.str());
  }
}

}  // namespace

void checkRunLength(const Scene& scene, const RunOptions& options) {
  const double dt = options.dtFor(scene), duration = options.duration.value_or(scene.duration);
  auto text = [](double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  };
  if (!std::isfinite(dt) || dt <= 0) throw std::invalid_argument("--dt: the step must be a positive number of seconds, not " + text(dt));
  if (!std::isfinite(duration) || duration <= 0)
    throw std::invalid_argument("--duration: must be a positive number of seconds, not " + text(duration));
  const double steps = std::round(duration / dt);
  if (steps < 1)
    throw std::invalid_argument("--duration: " + text(duration) + " s is shorter than one step of " + text(dt) + " s");
  if (steps > static_cast<double>(kMaxRunSteps))
    throw std::invalid_argument("--duration / --dt: " + text(duration) + " s in steps of " + text(dt) + " s is " +
                                text(steps) + " steps, more than " + text(static_cast<double>(kMaxRunSteps)));
}

nlohmann::ordered_json runScene(const Scene& scene, const RunOptions& options) {
  checkRunLength(scene, options);
  const long steps = options.stepsFor(scene);
  PolysimEngine engine(scene, options.method);
  std::unique_ptr<StepLog> log;
  if (!options.logPath.empty()) log = std::make_unique<StepLog>(options.logPath, options.logContacts);
  std::unique_ptr<ProgressBar> bar;
  if (options.progress) bar = std::make_unique<ProgressBar>(steps);

  long eventLimitSteps = 0, islandsJoined = 0, done = 0;
  const RunRecord record = recordRun(engine, steps, options.dtFor(scene), scene.up(), [&] {
    eventLimitSteps += engine.lastReport().eventLimitHit;
    islandsJoined += engine.lastReport().islandsJoined;
    if (log) log->write(engine.world(), engine.lastReport());
    if (bar) bar->update(++done);
    checkFinite(scene, engine.world());
  });
  nlohmann::ordered_json summary = summaryToJson(scene.name, record);
  summary["event_limit_steps"] = eventLimitSteps;
  summary["islands_joined"] = islandsJoined;
  summary["sleeping_bodies"] = engine.sleepingBodies();
  return summary;
}

}  // namespace polysim::sim
