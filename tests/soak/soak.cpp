// polysim_soak: a pile that keeps being refilled, for as many steps as asked (issue 18).
// Every `--refill-every` steps the lowest box is taken out from under the pile and dropped
// again from above it, turned at random, so the pile never settles for good: boxes fall
// into the gap, the dropped one lands on top, the pile wakes and sleeps again.
//
// Asserted at every step (exit 1 with the step and what broke):
// - every body's state is finite;
// - no blow-up: the energy never exceeds the starting energy plus what the refills added
//   plus lifting every box by the contact tolerance;
// - no committed overlap is deeper than the tolerance.
// Counted, not asserted: steps that raise the energy by more than that lift. A busy pile
// still has some (an island that reaches kMaxEventsPerStep, issue 15).
// Reported every `--report-every` steps, one JSON line: time, bodies asleep, energy, CPU
// ms per step since the last report, resident and peak resident memory (MB). With
// `--flat-memory-from N`, the run also fails if resident memory at the end exceeds
// what it was at step N by more than `--memory-slack` MB.
//
//   build/tests/soak/polysim_soak --steps 100000 --report-every 10000

#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <ctime>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <unistd.h>

#include "sim/scene.h"
#include "sim/step_log.h"
#include "sim/world.h"

namespace {

using namespace polysim;

struct SoakOptions {
  long steps = 2000;
  int boxes = 12;
  unsigned seed = 1;
  int refillEvery = 30;
  long reportEvery = 500;
  long flatMemoryFrom = 0;  // 0: no memory check
  double memorySlackMb = 4;
  std::string sceneOut;  // write the starting scene here too (for polysim run / view)
  std::string logPath;   // the step log, for polysim log / view
};

// The pen: a 1.75 m square floor inside 4 m walls (three to four 0.5 m boxes a side); the
// boxes start in layers of 2 x 2, far enough apart for any tilt up to kMaxTilt.
constexpr double kPenInside = 1.75, kWallHeight = 4.0, kWallThickness = 0.5, kBoxSize = 0.5, kGridSpacing = 0.85;
constexpr double kMaxTilt = 0.3;     // rad, the starting boxes' tilt
constexpr double kDropClearance = 0.5;  // m, a refill starts this far above the pile's top

std::string penScene(const SoakOptions& o) {
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  auto wall = [&](const char* name, double x, double y, double sx, double sy) {
    bodies.push_back({{"name", name}, {"static", true}, {"shape", {{"type", "box"}, {"size", {sx, sy, kWallHeight}}}},
                      {"position", {x, y, kWallHeight / 2}}});
  };
  const double w = kPenInside / 2 + kWallThickness / 2, span = kPenInside + 2 * kWallThickness;
  bodies.push_back({{"name", "floor"}, {"static", true}, {"shape", {{"type", "box"}, {"size", {span, span, 1.0}}}},
                    {"position", {0, 0, -0.5}}});
  wall("wall_x-", -w, 0, kWallThickness, span);
  wall("wall_x+", w, 0, kWallThickness, span);
  wall("wall_y-", 0, -w, kPenInside, kWallThickness);
  wall("wall_y+", 0, w, kPenInside, kWallThickness);
  std::mt19937 random(o.seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int i = 0; i < o.boxes; ++i) {
    const int column = i % 4, layer = i / 4;
    const Eigen::Vector3d axis = Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
    const Eigen::Quaterniond q(Eigen::AngleAxisd(kMaxTilt * std::abs(unit(random)), axis));
    bodies.push_back({{"name", "box" + std::to_string(i)},
                      {"shape", {{"type", "box"}, {"size", {kBoxSize, kBoxSize, kBoxSize}}}},
                      {"position", {(column % 2 - 0.5) * kGridSpacing, (column / 2 - 0.5) * kGridSpacing, 1.0 + layer * kGridSpacing}},
                      {"orientation", {q.w(), q.x(), q.y(), q.z()}}});
  }
  return nlohmann::ordered_json{{"name", "refilled_pile"}, {"dt", 1.0 / 60}, {"bodies", bodies}}.dump();
}

double residentMb() {
  long pages = 0, resident = 0;
  std::ifstream("/proc/self/statm") >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1 << 20);
}

double peakResidentMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024;  // KB on Linux
}

double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

bool finiteState(const dynamics::RigidBody& b) {
  return b.position.allFinite() && b.orientation.coeffs().allFinite() && b.velocity.allFinite() && b.angularVelocity.allFinite();
}

// Takes the lowest box out and drops it from above the pile, turned at random.
void refill(sim::World& world, std::mt19937& random) {
  const auto& bodies = world.bodies();
  int lowest = -1;
  double top = 0.0;
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    if (bodies[i].isStatic) continue;
    const double z = bodies[i].centerOfMass().z();
    top = std::max(top, z + kBoxSize);
    if (lowest < 0 || z < bodies[lowest].centerOfMass().z()) lowest = i;
  }
  std::uniform_real_distribution<double> unit(-1, 1);
  const double reach = kPenInside / 2 - kBoxSize;
  const Eigen::Quaterniond q = Eigen::Quaterniond::UnitRandom();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.toRotationMatrix();
  pose.translation() = Eigen::Vector3d(reach * unit(random), reach * unit(random), top + kDropClearance);
  world.placeBody(lowest, pose, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
}

int soak(const SoakOptions& o) {
  if (!o.sceneOut.empty()) std::ofstream(o.sceneOut) << penScene(o) << "\n";
  std::istringstream text(penScene(o));
  const sim::Scene scene = sim::readScene(text, "refilled_pile.json");
  sim::World world(scene);
  std::unique_ptr<sim::StepLog> log = o.logPath.empty() ? nullptr : std::make_unique<sim::StepLog>(o.logPath);
  double liftByTolerance = 0.0;  // J: every box lifted by the tolerance
  for (const dynamics::RigidBody& b : world.bodies())
    if (!b.isStatic) liftByTolerance += b.mass * scene.gravity.norm() * scene.contact.tolerance;
  std::mt19937 random(o.seed);
  double maxRise = 0.0, maxPenetration = 0.0, markCpu = cpuSeconds(), memoryAtMark = 0.0;
  double ceiling = world.energy();  // J: the start's energy plus every refill's
  long refills = 0, markStep = 0, risingSteps = 0, limitSteps = 0;
  auto fail = [&](long step, const std::string& what) {
    std::cerr << "polysim_soak: step " << step << " (t = " << world.time() << " s): " << what << "\n";
    return 1;
  };
  for (long step = 1; step <= o.steps; ++step) {
    if (step % o.refillEvery == 0) {
      const double before = world.energy();
      refill(world, random);
      ceiling += world.energy() - before;
      ++refills;
    }
    const double before = world.energy();
    const sim::StepReport& report = world.step(scene.dt);
    if (log) log->write(world, report);
    for (size_t i = 0; i < world.bodies().size(); ++i)
      if (!finiteState(world.bodies()[i])) return fail(step, "body \"" + scene.bodies[i].name + "\" is not finite");
    const double rise = world.energy() - before;
    maxRise = std::max(maxRise, rise);
    maxPenetration = std::max(maxPenetration, report.penetration);
    risingSteps += rise > liftByTolerance;
    limitSteps += report.eventLimitHit;
    if (world.energy() > ceiling + liftByTolerance)
      return fail(step, "the energy is " + std::to_string(world.energy()) + " J, more than the " +
                            std::to_string(ceiling) + " J the start and the refills gave");
    if (report.penetration > scene.contact.tolerance)
      return fail(step, "an overlap of " + std::to_string(report.penetration) + " m, deeper than the tolerance");
    if (step == o.flatMemoryFrom) memoryAtMark = residentMb();
    if (step % o.reportEvery == 0 || step == o.steps) {
      const double now = cpuSeconds();
      std::cout << nlohmann::ordered_json{{"step", step},
                                          {"t", world.time()},
                                          {"refills", refills},
                                          {"asleep", report.sleeping},
                                          {"energy_J", world.energy()},
                                          {"max_step_rise_J", maxRise},
                                          {"rising_steps", risingSteps},
                                          {"event_limit_steps", limitSteps},
                                          {"max_penetration_m", maxPenetration},
                                          {"cpu_ms_per_step", 1e3 * (now - markCpu) / static_cast<double>(step - markStep)},
                                          {"resident_MB", residentMb()},
                                          {"peak_resident_MB", peakResidentMb()}}
                       .dump()
                << std::endl;
      markCpu = now;
      markStep = step;
    }
  }
  if (o.flatMemoryFrom > 0 && residentMb() > memoryAtMark + o.memorySlackMb)
    return fail(o.steps, "resident memory grew from " + std::to_string(memoryAtMark) + " MB at step " +
                             std::to_string(o.flatMemoryFrom) + " to " + std::to_string(residentMb()) + " MB");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"polysim_soak: a pile that keeps being refilled, with its invariants asserted every step"};
  SoakOptions o;
  app.add_option("--steps", o.steps, "steps to run")->check(CLI::PositiveNumber);
  app.add_option("--boxes", o.boxes, "boxes in the pen")->check(CLI::Range(1, 200));
  app.add_option("--seed", o.seed, "seed of the tilts and the drops");
  app.add_option("--refill-every", o.refillEvery, "steps between refills")->check(CLI::PositiveNumber);
  app.add_option("--report-every", o.reportEvery, "steps between report lines")->check(CLI::PositiveNumber);
  app.add_option("--flat-memory-from", o.flatMemoryFrom, "fail if resident memory grows after this step");
  app.add_option("--memory-slack", o.memorySlackMb, "MB of growth allowed after --flat-memory-from");
  app.add_option("--scene-out", o.sceneOut, "also write the starting scene to this file");
  app.add_option("--log", o.logPath, "write the step log (polysim log, polysim view) to this file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }
  try {
    return soak(o);
  } catch (const std::exception& e) {
    std::cerr << "polysim_soak: " << e.what() << "\n";
    return 1;
  }
}
