#pragma once
// `polysim sweep`: the standard scenes run by both engines over their settings, each run
// scored for cost (CPU and wall time per simulated second) and for error against the
// analytic answer (analytic_reference.h). The rows feed the speed-versus-accuracy chart.
// A sweep is a list of independent runs (sweepRuns); sweep_plan.h hands them out as
// separate command lines.

#include <iosfwd>
#include <string>
#include <vector>

namespace polysim::sim {

/// One engine setting.
struct SweepSetting {
  std::string engine;         // "polysim" or "ode"
  std::string solver;         // polysim: "bisection" / "regula-falsi"; ode: "worldstep" / "quickstep"
  std::string parameterName;  // "tolerance_m" or "solver_sweeps" (polysim), "iterations" (quickstep), "none" (worldstep)
  double parameter = 0.0;     // its value; 0 for "none"
  double dt = 0.0;            // s
};

/// A scene of the standard set and what it measures: first_contact_time (s), rest_height
/// (m), bounce_apex (m), slide_distance (m), stack_drift (m: the largest horizontal
/// displacement of any body, analytic 0), max_penetration (m, analytic 0), displacement
/// (m: the farthest any body ended from its start, analytic 0 for a pyramid that stands),
/// energy_gain (J: the run's largest rise of energy above its start, analytic 0),
/// time_to_rest (s: RunRecord::timeToRest, the run's length when it never came to rest;
/// it has no analytic answer: 0 stands in, and the error is the time itself).
struct SweepCase {
  std::string scene;  // file name in the scenes directory, without ".json"
  double duration;    // s
  std::vector<std::string> metrics;
  std::string body = "box";  // the body dropped, bounced or slid
  std::string ramp;          // the static body it slides on (slide_distance)
};

/// One measured figure of one run.
struct SweepRow {
  std::string scene;
  SweepSetting setting;
  double wallTime = 0.0;  // s
  double cost = 0.0;      // s of wall time per simulated second
  double cpuTime = 0.0;   // s, the stepping thread's CPU time (RunRecord::cpuTime)
  double cpuCost = 0.0;   // s of CPU time per simulated second
  std::string metric;
  double measured = 0.0, analytic = 0.0, error = 0.0;  // error = |measured - analytic|
  long solverWarnings = 0;  // ODE's warnings in the run (OdeMessageLog); 0 for polysim
};

struct SweepOptions {
  std::string scenesDirectory = "scenes";
  /// Two steps, one setting per solver, short runs and the 5-box stack instead of the
  /// 10-box one: for tests. The full sweep is the default.
  bool quick = false;
};

std::vector<SweepCase> standardSweepCases(bool quick);
std::vector<SweepSetting> sweepSettings(bool quick);

/// Throws std::invalid_argument naming the case when the standard set has none of that name.
const SweepCase& standardSweepCase(const std::string& scene, bool quick);

/// One run of the sweep: a case under a setting.
struct SweepRun {
  SweepCase sweepCase;
  SweepSetting setting;
};

/// Every case under every setting, case by case: the sweep's runs in its CSV's order.
std::vector<SweepRun> sweepRuns(bool quick);

/// A name for the run made of its case and setting (no spaces, no slashes), e.g.
/// "drop_box.polysim.bisection.tolerance_m=0.0001.dt=0.0166667": the file name of its
/// result in a planned sweep. Distinct runs of one sweep have distinct names.
std::string sweepRunName(const SweepRun& run);

/// Runs one run on the case's scene from `scenesDirectory`: a row per measure of the case.
/// `progress` (when given) gets one line.
std::vector<SweepRow> runSweepRun(const std::string& scenesDirectory, const SweepRun& run,
                                  std::ostream* progress = nullptr);

/// Runs every run of the sweep, in order. `progress` (when given) gets one line per run.
std::vector<SweepRow> runSweep(const SweepOptions& options, std::ostream* progress = nullptr);

}  // namespace polysim::sim
