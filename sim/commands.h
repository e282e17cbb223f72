#pragma once
// The polysim subcommands, as functions: each reads its inputs, writes its JSON result to
// `out` and returns the process exit code. Errors are thrown (SceneError and others) and
// turned into one message on stderr by main().

#include <iosfwd>
#include <string>

namespace polysim::sim {

/// `polysim contacts SCENE`: test4Intersection() on the initial state.
int contactsCommand(const std::string& scenePath, std::ostream& out);

/// `polysim run SCENE [--duration S] [--dt S] [--log FILE]`: the summary as JSON.
int runCommand(const std::string& scenePath, const struct RunOptions& options, std::ostream& out);

/// `polysim toc SCENE [--interval T] [--method M]`: collisionDetect() over [0, T] with
/// every moving body kinematic (constant velocity and angular velocity); T <= 0 means
/// the scene's dt. `method` is "bisection" or "regula-falsi".
int tocCommand(const std::string& scenePath, double interval, const std::string& method, std::ostream& out);

/// `polysim compare SCENE [--duration S] [--dt S]`: both engines' summaries and their
/// comparison (ode_baseline.h).
int compareCommand(const std::string& scenePath, const struct RunOptions& options, const struct OdeSettings& ode,
                   std::ostream& out);

/// `polysim sweep [--scenes DIR] [--quick] [--out FILE]`: the speed-versus-accuracy CSV
/// (sweep.h). With a file, the CSV is written whole at the end (to FILE.partial, then
/// renamed), so that an interrupted sweep leaves no half-written file; otherwise to `out`.
/// `progress`, when given, gets a line per run.
int sweepCommand(const struct SweepOptions& options, const std::string& outPath, std::ostream& out,
                 std::ostream* progress);

/// `polysim sweep [--scenes DIR] [--quick] --plan FILE [--results DIR]`: the sweep as a job
/// list (sweep_plan.h), written whole to FILE; runs nothing. `binary` is the polysim the
/// lines call.
int sweepPlanCommand(const struct SweepOptions& options, const std::string& planPath, const std::string& resultsDirectory,
                     const std::string& binary);

/// `polysim sweep [--scenes DIR] [--quick] --case SCENE --engine E --solver S --parameter P
/// --dt S --out FILE`: one planned run. Says on `note` when FILE already held its rows.
int sweepRunCommand(const struct SweepOptions& options, const struct SweepRun& run, const std::string& outPath,
                    std::ostream& note);

/// `polysim sweep [--quick] --merge DIR [--out FILE]`: the runs' rows as the sweep's CSV, to
/// FILE (whole) or `out`; `report` names each run not merged. Returns 1 when a run was
/// not merged (the CSV then holds the others), else 0.
int sweepMergeCommand(const std::string& resultsDirectory, bool quick, const std::string& outPath, std::ostream& out,
                      std::ostream& report);

/// `polysim make KIND [--count N] [--seed S] [--tilt RAD] [--dt S] [--duration S] [--out
/// FILE]`: a generated scene (scene_generators.h), to FILE (written whole or not at all)
/// or to `out`. The same options give the same bytes.
int makeCommand(const struct MakeOptions& options, const std::string& outPath, std::ostream& out);

/// `polysim view LOG... [--scene SCENE] [--out FILE.html]`: the replay page (view_page.h);
/// prints {"page": path, "bytes": its size}.
int viewCommand(const struct ViewOptions& options, std::ostream& out);

}  // namespace polysim::sim
