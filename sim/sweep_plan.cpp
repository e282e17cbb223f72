#include "sim/sweep_plan.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "sim/sweep_csv.h"
#include "sim/whole_file.h"

namespace polysim::sim {
namespace {

namespace fs = std::filesystem;

// `text` as one shell word: as it is when it needs no quoting, else in single quotes.
std::string shellWord(const std::string& text) {
  const std::string plain = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:+,@%";
  if (!text.empty() && text.find_first_not_of(plain) == std::string::npos) return text;
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string failedMarker(const std::string& outPath) { return outPath + ".failed"; }

// Empty when `path` holds `run`'s rows, whole; else why not.
std::string whyNotWhole(const std::string& path, const SweepRun& run, std::vector<SweepRow>* rows = nullptr) {
  std::ifstream file(path);
  if (!file) return "cannot be read";
  std::vector<SweepRow> read;
  try {
    read = readSweepCsv(file, path);
  } catch (const std::exception& e) {
    return e.what();
  }
  const std::vector<std::string>& metrics = run.sweepCase.metrics;
  if (read.size() != metrics.size())
    return path + ": " + std::to_string(read.size()) + " rows, not " + std::to_string(metrics.size());
  for (size_t i = 0; i < read.size(); ++i) {
    const SweepRow& r = read[i];
    const SweepSetting& s = run.setting;
    if (r.scene != run.sweepCase.scene || r.metric != metrics[i] || r.setting.engine != s.engine ||
        r.setting.solver != s.solver || r.setting.parameterName != s.parameterName ||
        r.setting.parameter != s.parameter || r.setting.dt != s.dt)
      return path + ": line " + std::to_string(i + 2) + " is not a figure of this run";
  }
  if (rows) *rows = read;
  return "";
}

std::string firstLineOf(const std::string& path) {
  std::ifstream file(path);
  std::string line;
  std::getline(file, line);
  return line.empty() ? "(no message)" : line;
}

}  // namespace

SweepSetting sweepSettingFrom(const std::string& engine, const std::string& solver, const std::string& parameterName,
                              double parameter, double dt) {
  if (!(dt > 0)) throw std::invalid_argument("--dt: the step must be positive");
  auto wholeNumber = [](double x) { return x >= 1 && x == static_cast<double>(static_cast<long>(x)); };
  if (engine == "polysim") {
    if (solver != "bisection" && solver != "regula-falsi")
      throw std::invalid_argument("--solver: polysim's solvers are bisection and regula-falsi, not \"" + solver + "\"");
    if (parameterName == "solver_sweeps") {
      if (!wholeNumber(parameter)) throw std::invalid_argument("--parameter: polysim's solver sweeps must be a positive whole number");
      return {engine, solver, parameterName, parameter, dt};
    }
    if (!parameterName.empty() && parameterName != "tolerance_m")
      throw std::invalid_argument("--parameter-name: polysim's are tolerance_m and solver_sweeps, not \"" + parameterName + "\"");
    if (!(parameter > 0)) throw std::invalid_argument("--parameter: polysim's tolerance (m) must be positive");
    return {engine, solver, "tolerance_m", parameter, dt};
  }
  if (engine == "ode") {
    auto checkName = [&](const char* own) {
      if (!parameterName.empty() && parameterName != own)
        throw std::invalid_argument("--parameter-name: ODE's " + solver + " takes " + own + ", not \"" + parameterName + "\"");
    };
    if (solver == "worldstep") {
      checkName("none");
      if (parameter != 0) throw std::invalid_argument("--parameter: ODE's worldstep takes none (give 0)");
      return {engine, solver, "none", 0.0, dt};
    }
    if (solver != "quickstep")
      throw std::invalid_argument("--solver: ODE's solvers are worldstep and quickstep, not \"" + solver + "\"");
    checkName("iterations");
    if (!wholeNumber(parameter))
      throw std::invalid_argument("--parameter: quickstep's iterations must be a positive whole number");
    return {engine, solver, "iterations", parameter, dt};
  }
  throw std::invalid_argument("--engine: polysim or ode, not \"" + engine + "\"");
}

void writeSweepPlan(const SweepOptions& options, const std::string& resultsDirectory, const std::string& binary,
                    std::ostream& out) {
  std::error_code error;
  fs::create_directories(resultsDirectory, error);
  if (error || !fs::is_directory(resultsDirectory))
    throw std::runtime_error(resultsDirectory + ": cannot make the results folder");
  const std::string scenes = fs::absolute(options.scenesDirectory).lexically_normal().string();
  const std::string results = fs::absolute(resultsDirectory).lexically_normal().string();
  std::ostringstream number;  // full precision, so the run's setting reads back as the same double
  number << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (const SweepRun& run : sweepRuns(options.quick)) {
    const SweepSetting& s = run.setting;
    number.str("");
    number << s.parameter << " --dt " << s.dt;
    out << shellWord(binary) << " sweep --scenes " << shellWord(scenes) << (options.quick ? " --quick" : "")
        << " --case " << shellWord(run.sweepCase.scene) << " --engine " << s.engine << " --solver " << s.solver
        << " --parameter-name " << s.parameterName << " --parameter " << number.str() << " --out "
        << shellWord((fs::path(results) / (sweepRunName(run) + ".csv")).string()) << "\n";
  }
}

PlannedRunOutcome runPlannedSweepRun(const std::string& scenesDirectory, const SweepRun& run,
                                     const std::string& outPath) {
  if (fs::exists(outPath) && whyNotWhole(outPath, run).empty()) {
    std::remove(failedMarker(outPath).c_str());
    return PlannedRunOutcome::kKept;
  }
  try {
    const std::vector<SweepRow> rows = runSweepRun(scenesDirectory, run);
    writeWholeFile(outPath, "the run's rows", [&](std::ostream& file) { writeSweepCsv(rows, file); });
  } catch (const std::exception& e) {
    try {
      writeWholeFile(failedMarker(outPath), "the run's failure", [&](std::ostream& file) { file << e.what() << "\n"; });
    } catch (const std::exception&) {  // the run's own error is the one to report
    }
    throw;
  }
  std::remove(failedMarker(outPath).c_str());
  return PlannedRunOutcome::kRan;
}

SweepMerge mergeSweep(const std::string& resultsDirectory, bool quick) {
  if (!fs::is_directory(resultsDirectory)) throw std::runtime_error(resultsDirectory + ": not a folder of sweep results");
  SweepMerge merge;
  for (const SweepRun& run : sweepRuns(quick)) {
    ++merge.runs;
    const std::string name = sweepRunName(run);
    const std::string path = (fs::path(resultsDirectory) / (name + ".csv")).string();
    std::vector<SweepRow> rows;
    if (fs::exists(path)) {
      const std::string why = whyNotWhole(path, run, &rows);
      if (!why.empty()) {
        merge.notMerged.push_back(name + ": cut short or not this run's: " + why);
        continue;
      }
      merge.rows.insert(merge.rows.end(), rows.begin(), rows.end());
      ++merge.merged;
    } else if (fs::exists(failedMarker(path))) {
      merge.notMerged.push_back(name + ": failed: " + firstLineOf(failedMarker(path)));
    } else {
      merge.notMerged.push_back(name + ": missing");
    }
  }
  return merge;
}

}  // namespace polysim::sim
