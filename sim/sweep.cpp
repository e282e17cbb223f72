#include "sim/sweep.h"

#include <cmath>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "sim/analytic_reference.h"
#include "sim/ode_world.h"
#include "sim/polysim_engine.h"
#include "sim/run_record.h"

namespace polysim::sim {
namespace {

const BodyState& stateOf(const std::vector<BodyState>& states, const std::string& name) {
  for (const BodyState& s : states)
    if (s.name == name) return s;
  throw std::invalid_argument("the sweep measures body \"" + name + "\", which is not a dynamic body of the scene");
}

struct Figure {
  double measured, analytic;
};

Figure measure(const std::string& metric, const SweepCase& c, const Scene& scene, const RunRecord& r) {
  const Eigen::Vector3d& up = r.up;
  if (metric == "first_contact_time")  // none: not before the end of the run
    return {r.firstContactTime.value_or(r.simTime), dropReference(scene, c.body).firstContactTime};
  if (metric == "rest_height") return {stateOf(r.final, c.body).position.dot(up), dropReference(scene, c.body).restHeight};
  if (metric == "bounce_apex") {
    const double apex = r.apexAfterFirstContact[&stateOf(r.final, c.body) - r.final.data()];
    return {std::isnan(apex) ? stateOf(r.final, c.body).position.dot(up) : apex, dropReference(scene, c.body).bounceApex};
  }
  if (metric == "slide_distance")
    return {(stateOf(r.final, c.body).position - stateOf(r.initial, c.body).position).norm(),
            inclineSlideDistance(scene, c.body, c.ramp, r.simTime)};
  if (metric == "stack_drift") {
    double drift = 0.0;
    for (size_t i = 0; i < r.final.size(); ++i) drift = std::max(drift, r.drift(i));
    return {drift, 0.0};
  }
  if (metric == "max_penetration") return {r.maxPenetration, 0.0};
  if (metric == "energy_gain") return {r.maxEnergyIncrease, 0.0};  // nothing adds energy to these scenes
  // No analytic answer: 0 stands in, so that the error is the time itself (the run's
  // length when it never came to rest). Compare settings by it, not against 0: a pile
  // takes time to settle however exact the engine.
  if (metric == "time_to_rest") return {r.timeToRest.value_or(r.simTime), 0.0};
  if (metric == "displacement") {  // a pyramid that stands: every box where it started
    double farthest = 0.0;
    for (size_t i = 0; i < r.final.size(); ++i) farthest = std::max(farthest, (r.final[i].position - r.initial[i].position).norm());
    return {farthest, 0.0};
  }
  throw std::invalid_argument("unknown sweep metric \"" + metric + "\"");
}

// One run; `warnings` gets ODE's solver warnings (0 for polysim).
RunRecord runOnce(const Scene& scene, const SweepCase& c, const SweepSetting& s, long& warnings) {
  warnings = 0;
  const long steps = std::lround(c.duration / s.dt);
  if (s.engine == "polysim") {
    Scene tuned = scene;
    if (s.parameterName == "solver_sweeps") tuned.contact.solverSweeps = static_cast<int>(s.parameter);
    else tuned.contact.tolerance = s.parameter;
    PolysimEngine engine(tuned, collision::tocMethodNamed(s.solver));
    return recordRun(engine, steps, s.dt, scene.up());
  }
  OdeSettings ode;
  ode.quickStep = s.solver == "quickstep";
  if (ode.quickStep) ode.quickStepIterations = static_cast<int>(s.parameter);
  OdeWorld engine(scene, ode);
  RunRecord record = recordRun(engine, steps, s.dt, scene.up());
  warnings = engine.messages();
  return record;
}

}  // namespace

std::vector<SweepCase> standardSweepCases(bool quick) {
  std::vector<SweepCase> cases = {{"drop_box", quick ? 2.0 : 3.0, {"first_contact_time", "rest_height", "max_penetration"}, "box", ""},
          {"bounce", 1.5, {"bounce_apex"}, "box", ""},
          {"ramp_slides", 1.0, {"slide_distance"}, "box", "ramp"},
          {quick ? "stack_5" : "stack_10", quick ? 2.0 : 10.0, {"stack_drift", "max_penetration"}, "", ""},
          // Busy scenes (polysim make ..., see README): many contacts at once.
          {quick ? "pyramid" : "pyramid_10", quick ? 1.0 : 5.0, {"displacement", "energy_gain", "time_to_rest"}, "", ""}};
  if (quick) return cases;
  cases.push_back({"pile_27", 4.0, {"energy_gain", "max_penetration", "time_to_rest"}, "", ""});
  cases.push_back({"dominoes_10", 6.0, {"energy_gain", "max_penetration", "time_to_rest"}, "", ""});
  return cases;
}

std::vector<SweepSetting> sweepSettings(bool quick) {
  const std::vector<double> dts = quick ? std::vector<double>{1.0 / 60, 1.0 / 240}
                                        : std::vector<double>{1.0 / 60, 1.0 / 120, 1.0 / 240, 1.0 / 480};
  const std::vector<double> tolerances = quick ? std::vector<double>{1e-4} : std::vector<double>{1e-3, 1e-4, 1e-5};
  const std::vector<int> iterations = quick ? std::vector<int>{20} : std::vector<int>{10, 20, 50};
  // Beside the default (200, of which only a settling group uses more than 60): fewer,
  // and more.
  const std::vector<int> solverSweeps = quick ? std::vector<int>{30} : std::vector<int>{20, 600};
  std::vector<SweepSetting> settings;
  for (double dt : dts) {
    for (const char* method : {"bisection", "regula-falsi"})
      for (double tolerance : tolerances) settings.push_back({"polysim", method, "tolerance_m", tolerance, dt});
    // The solver's sweep limit, at the default tolerance (the default is the row above).
    for (int sweeps : solverSweeps) settings.push_back({"polysim", "regula-falsi", "solver_sweeps", static_cast<double>(sweeps), dt});
    settings.push_back({"ode", "worldstep", "none", 0.0, dt});
    for (int n : iterations) settings.push_back({"ode", "quickstep", "iterations", static_cast<double>(n), dt});
  }
  return settings;
}

const SweepCase& standardSweepCase(const std::string& scene, bool quick) {
  static const std::vector<SweepCase> full = standardSweepCases(false), short_ = standardSweepCases(true);
  for (const SweepCase& c : quick ? short_ : full)
    if (c.scene == scene) return c;
  throw std::invalid_argument("the " + std::string(quick ? "quick " : "") + "sweep has no case \"" + scene + "\"");
}

std::vector<SweepRun> sweepRuns(bool quick) {
  std::vector<SweepRun> runs;
  for (const SweepCase& c : standardSweepCases(quick))
    for (const SweepSetting& s : sweepSettings(quick)) runs.push_back({c, s});
  return runs;
}

std::string sweepRunName(const SweepRun& run) {
  const SweepSetting& s = run.setting;
  std::ostringstream name;
  name << run.sweepCase.scene << "." << s.engine << "." << s.solver << "." << s.parameterName << "=" << s.parameter
       << ".dt=" << s.dt;  // 6 significant digits tell the sweep's steps and parameters apart
  return name.str();
}

std::vector<SweepRow> runSweepRun(const std::string& scenesDirectory, const SweepRun& run, std::ostream* progress) {
  const SweepCase& c = run.sweepCase;
  const SweepSetting& s = run.setting;
  const Scene scene = loadScene(scenesDirectory + "/" + c.scene + ".json");
  long warnings = 0;
  const RunRecord record = runOnce(scene, c, s, warnings);
  if (progress)
    *progress << c.scene << " " << s.engine << " " << s.solver << " " << s.parameterName << "=" << s.parameter
              << " dt=" << s.dt << ": " << record.wallTime << " s" << (warnings ? ", ODE warnings: " : "")
              << (warnings ? std::to_string(warnings) : "") << "\n";
  std::vector<SweepRow> rows;
  for (const std::string& metric : c.metrics) {
    const Figure f = measure(metric, c, scene, record);
    rows.push_back({c.scene, s, record.wallTime, record.wallTime / record.simTime, record.cpuTime,
                    record.cpuTime / record.simTime, metric, f.measured, f.analytic, std::abs(f.measured - f.analytic),
                    warnings});
  }
  return rows;
}

std::vector<SweepRow> runSweep(const SweepOptions& options, std::ostream* progress) {
  std::vector<SweepRow> rows;
  for (const SweepRun& run : sweepRuns(options.quick)) {
    std::vector<SweepRow> runRows = runSweepRun(options.scenesDirectory, run, progress);
    rows.insert(rows.end(), runRows.begin(), runRows.end());
  }
  return rows;
}

}  // namespace polysim::sim
