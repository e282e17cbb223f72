#pragma once
// A sweep handed out as a job list: `polysim sweep --plan` writes one self-contained
// `polysim sweep --case ...` command line per run, for GNU parallel, ssh hosts or a Slurm
// array to run in any order and any number at once; each run writes its own rows whole
// into the results folder; `polysim sweep --merge` collects them into the sweep's CSV in
// the sweep's order and names every run that is missing, failed or cut short.

#include <iosfwd>
#include <string>
#include <vector>

#include "sim/sweep.h"

namespace polysim::sim {

/// The setting a planned run's command line names. `parameterName` may be empty for the
/// engine's usual one (polysim: tolerance_m; its other is solver_sweeps). Throws
/// std::invalid_argument naming the option at fault: an engine other than polysim / ode, a
/// solver or parameter name the engine does not have, a tolerance (polysim) that is not
/// positive, solver sweeps or iterations (quickstep) that are not a positive whole number,
/// a parameter given to worldstep, a dt that is not positive.
SweepSetting sweepSettingFrom(const std::string& engine, const std::string& solver, const std::string& parameterName,
                              double parameter, double dt);

/// Writes the plan: one line per run of the sweep (sweepRuns), each a shell command that
/// runs `binary` on that run alone and writes its rows to `resultsDirectory`/NAME.csv
/// (NAME: sweepRunName). Paths are made absolute, so that a line runs the same from any
/// folder on a shared file system. Creates `resultsDirectory`; runs nothing.
void writeSweepPlan(const SweepOptions& options, const std::string& resultsDirectory, const std::string& binary,
                    std::ostream& out);

/// What a planned run did.
enum class PlannedRunOutcome { kRan, kKept };

/// Runs one run and writes its rows to `outPath` whole (whole_file.h). Resumable: when
/// `outPath` already holds this run's rows, whole, it is kept and nothing runs. When the
/// run fails, `outPath`.failed is left holding the message for the merge, and the
/// exception goes on; a later success removes it.
PlannedRunOutcome runPlannedSweepRun(const std::string& scenesDirectory, const SweepRun& run,
                                     const std::string& outPath);

/// The merge of a results folder: the rows of every whole run, in the sweep's order, and
/// one line per run of the sweep that is not among them ("NAME: missing", "NAME: failed:
/// MESSAGE", "NAME: cut short or not this run's: WHY").
struct SweepMerge {
  std::vector<SweepRow> rows;
  size_t runs = 0, merged = 0;
  std::vector<std::string> notMerged;
};

/// Merges `resultsDirectory` against the sweep that `quick` names (the plan's --quick).
/// Throws std::runtime_error when the folder cannot be read.
SweepMerge mergeSweep(const std::string& resultsDirectory, bool quick);

}  // namespace polysim::sim
