// The pieces of a planned sweep: the CSV read back exactly or refused with its line, run
// names that tell every run apart, settings checked as a command line gives them, a run
// kept when its results are whole and its failure left for the merge.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <unistd.h>

#include "sim/sweep.h"
#include "sim/sweep_csv.h"
#include "sim/sweep_plan.h"

namespace polysim::sim {
namespace {

namespace fs = std::filesystem;

SweepRow someRow() {
  SweepRow r;
  r.scene = "drop_box";
  r.setting = {"polysim", "bisection", "tolerance_m", 1e-4, 1.0 / 60};
  r.wallTime = 0.1 / 3;
  r.cost = 1.0 / 7;
  r.cpuTime = 2.0 / 3;
  r.cpuCost = 1e-5 / 3;
  r.metric = "first_contact_time";
  r.measured = 0.55299479166666676;
  r.analytic = std::sqrt(3.0 / 9.81);
  r.error = std::abs(r.measured - r.analytic);
  r.solverWarnings = 3;
  return r;
}

std::string csvOf(const std::vector<SweepRow>& rows) {
  std::ostringstream out;
  writeSweepCsv(rows, out);
  return out.str();
}

std::vector<SweepRow> read(const std::string& text) {
  std::istringstream in(text);
  return readSweepCsv(in, "x.csv");
}

std::string errorReading(const std::string& text) {
  try {
    read(text);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(SweepCsv, ReadsBackTheSameDoubles) {
  const SweepRow r = someRow();
  const std::vector<SweepRow> back = read(csvOf({r, r}));
  ASSERT_EQ(back.size(), 2u);
  for (const SweepRow& b : back) {
    EXPECT_EQ(b.scene, r.scene);
    EXPECT_EQ(b.setting.parameterName, r.setting.parameterName);
    EXPECT_EQ(b.setting.dt, r.setting.dt);
    for (auto [got, want] : {std::pair{b.wallTime, r.wallTime}, {b.cost, r.cost}, {b.cpuTime, r.cpuTime},
                             {b.cpuCost, r.cpuCost}, {b.measured, r.measured}, {b.analytic, r.analytic},
                             {b.error, r.error}})
      EXPECT_EQ(got, want);  // exactly: full precision both ways
    EXPECT_EQ(b.solverWarnings, 3);
  }
}

TEST(SweepCsv, RefusesWhatItDidNotWriteNamingTheLineAndColumn) {
  const std::string whole = csvOf({someRow(), someRow()});
  EXPECT_EQ(errorReading(""), "x.csv: empty, not a sweep CSV");
  EXPECT_EQ(errorReading("scene,engine\n"), "x.csv: line 1 is not the sweep CSV's header");
  EXPECT_EQ(errorReading(whole.substr(0, whole.size() - 1)), "x.csv: line 3 has no newline: the file was cut short");
  std::string noNumber = whole;
  noNumber.replace(noNumber.find("0.0001"), 6, "0.0001x");
  EXPECT_EQ(errorReading(noNumber), "x.csv: line 2: column parameter is not a finite number: \"0.0001x\"");
  std::string infinite = whole;
  infinite.replace(infinite.find(",3,"), 3, ",inf,");
  EXPECT_EQ(errorReading(infinite), "x.csv: line 2: column solver_warnings is not a finite number: \"inf\"");
  std::string shortLine = whole;
  shortLine.erase(shortLine.find("first_contact_time,"), 19);
  EXPECT_EQ(errorReading(shortLine), "x.csv: line 2 has 14 fields, not 15");
  std::string empty = whole;
  empty.replace(empty.find("bisection"), 9, "");
  EXPECT_EQ(errorReading(empty), "x.csv: line 2: column solver is empty");
}

TEST(SweepPlan, EveryRunOfTheFullSweepHasItsOwnName) {
  std::set<std::string> names;
  for (bool quick : {false, true})
    for (const SweepRun& run : sweepRuns(quick)) {
      const std::string name = sweepRunName(run);
      EXPECT_EQ(name.find_first_of(" /"), std::string::npos) << name;
      names.insert(std::to_string(quick) + name);
    }
  EXPECT_EQ(names.size(), sweepRuns(false).size() + sweepRuns(true).size());
  EXPECT_EQ(sweepRunName({standardSweepCase("drop_box", true), {"polysim", "bisection", "tolerance_m", 1e-4, 1.0 / 60}}),
            "drop_box.polysim.bisection.tolerance_m=0.0001.dt=0.0166667");
}

TEST(SweepPlan, SettingsFromACommandLineAreChecked) {
  const SweepSetting polysim = sweepSettingFrom("polysim", "regula-falsi", "", 1e-5, 0.01);
  EXPECT_EQ(polysim.parameterName, "tolerance_m");
  EXPECT_EQ(sweepSettingFrom("polysim", "regula-falsi", "tolerance_m", 1e-5, 0.01).parameterName, "tolerance_m");
  const SweepSetting sweeps = sweepSettingFrom("polysim", "regula-falsi", "solver_sweeps", 20, 0.01);
  EXPECT_EQ(sweeps.parameterName, "solver_sweeps");
  EXPECT_EQ(sweeps.parameter, 20);
  EXPECT_EQ(sweepSettingFrom("ode", "quickstep", "", 20, 0.01).parameterName, "iterations");
  EXPECT_EQ(sweepSettingFrom("ode", "worldstep", "", 0, 0.01).parameterName, "none");
  EXPECT_THROW(sweepSettingFrom("bullet", "bisection", "", 1e-4, 0.01), std::invalid_argument);
  EXPECT_THROW(sweepSettingFrom("polysim", "quickstep", "", 1e-4, 0.01), std::invalid_argument);
  EXPECT_THROW(sweepSettingFrom("polysim", "bisection", "", 0, 0.01), std::invalid_argument);
  EXPECT_THROW(sweepSettingFrom("polysim", "bisection", "solver_sweeps", 2.5, 0.01), std::invalid_argument);
  EXPECT_THROW(sweepSettingFrom("polysim", "bisection", "solver_sweeps", 0, 0.01), std::invalid_argument);
  EXPECT_THROW(sweepSettingFrom("polysim", "bisection", "iterations", 20, 0.01), std::invalid_argument);
  EXPECT_THROW(sweepSettingFrom("ode", "quickstep", "tolerance_m", 20, 0.01), std::invalid_argument);
  EXPECT_THROW(sweepSettingFrom("ode", "worldstep", "iterations", 0, 0.01), std::invalid_argument);
  try {  // the engine is what is wrong, whatever the parameter's name
    sweepSettingFrom("bullet", "quickstep", "iterations", 20, 0.01);
    ADD_FAILURE() << "an unknown engine was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--engine", 0), 0u) << e.what();
  }
  EXPECT_THROW(sweepSettingFrom("ode", "quickstep", "", 2.5, 0.01), std::invalid_argument);
  EXPECT_THROW(sweepSettingFrom("ode", "worldstep", "", 3, 0.01), std::invalid_argument);
  EXPECT_THROW(sweepSettingFrom("ode", "worldstep", "", 0, 0), std::invalid_argument);
  EXPECT_THROW(standardSweepCase("stack_10", true), std::invalid_argument);  // the quick sweep has stack_5
}

class PlannedRun : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: ctest runs tests side by side.
    dir_ = fs::temp_directory_path() / ("polysim-planned-run-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  const SweepRun run_{standardSweepCase("drop_box", true), {"ode", "worldstep", "none", 0.0, 1.0 / 60}};
};

TEST_F(PlannedRun, KeepsWholeResultsAndRunsAgainWhatIsCutShort) {
  const std::string out = (dir_ / "run.csv").string();
  EXPECT_EQ(runPlannedSweepRun(POLYSIM_SCENES_DIR, run_, out), PlannedRunOutcome::kRan);
  EXPECT_EQ(runPlannedSweepRun(POLYSIM_SCENES_DIR, run_, out), PlannedRunOutcome::kKept);
  std::ifstream in(out);
  EXPECT_EQ(readSweepCsv(in, out).size(), run_.sweepCase.metrics.size());
  fs::resize_file(out, fs::file_size(out) - 5);
  EXPECT_EQ(runPlannedSweepRun(POLYSIM_SCENES_DIR, run_, out), PlannedRunOutcome::kRan);
  // Another run's rows in the file are not this run's.
  SweepRun other = run_;
  other.setting.dt = 1.0 / 240;
  EXPECT_EQ(runPlannedSweepRun(POLYSIM_SCENES_DIR, other, out), PlannedRunOutcome::kRan);
}

TEST_F(PlannedRun, AFailureLeavesItsMessageForTheMergeAndNoResult) {
  const std::string out = (dir_ / "run.csv").string();
  EXPECT_THROW(runPlannedSweepRun((dir_ / "no_scenes").string(), run_, out), std::exception);
  EXPECT_FALSE(fs::exists(out));
  std::ifstream marker(out + ".failed");
  std::string message;
  std::getline(marker, message);
  EXPECT_NE(message.find("drop_box.json"), std::string::npos) << message;
  runPlannedSweepRun(POLYSIM_SCENES_DIR, run_, out);
  EXPECT_FALSE(fs::exists(out + ".failed"));  // the success replaces the failure
}

TEST(SweepMerge, NamesEveryRunOfTheSweepItHasNot) {
  const fs::path dir = fs::temp_directory_path() / ("polysim-empty-merge-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const SweepMerge merge = mergeSweep(dir.string(), true);
  fs::remove_all(dir);
  EXPECT_EQ(merge.runs, sweepRuns(true).size());
  EXPECT_EQ(merge.merged, 0u);
  ASSERT_EQ(merge.notMerged.size(), merge.runs);
  EXPECT_EQ(merge.notMerged[0], sweepRunName(sweepRuns(true)[0]) + ": missing");
  EXPECT_THROW(mergeSweep("/nonexistent-polysim-folder", true), std::runtime_error);
}

}  // namespace
}  // namespace polysim::sim
