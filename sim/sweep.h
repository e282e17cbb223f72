#pragma once
// `polysim sweep`: the standard scenes run by both engines over their settings, each run
// scored for cost (wall time per simulated second) and for error against the analytic
// answer (analytic_reference.h). The rows feed the speed-versus-accuracy chart.

#include <iosfwd>
#include <string>
#include <vector>

namespace polysim::sim {

/// One engine setting.
struct SweepSetting {
  std::string engine;         // "polysim" or "ode"
  std::string solver;         // polysim: "bisection" / "regula-falsi"; ode: "worldstep" / "quickstep"
  std::string parameterName;  // "tolerance_m" (polysim), "iterations" (quickstep), "none" (worldstep)
  double parameter = 0.0;     // its value; 0 for "none"
  double dt = 0.0;            // s
};

/// A scene of the standard set and what it measures: first_contact_time (s), rest_height
/// (m), bounce_apex (m), slide_distance (m), stack_drift (m: the largest horizontal
/// displacement of any body, analytic 0), max_penetration (m, analytic 0).
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

/// Runs every case under every setting. `progress` (when given) gets one line per run.
std::vector<SweepRow> runSweep(const SweepOptions& options, std::ostream* progress = nullptr);

/// CSV with a header: scene, engine, solver, parameter_name, parameter, dt, wall_s,
/// cost_s_per_s, metric, measured, analytic, error, solver_warnings. Numbers at full
/// precision.
void writeSweepCsv(const std::vector<SweepRow>& rows, std::ostream& out);

}  // namespace polysim::sim
