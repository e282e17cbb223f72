// The step log written by a run, read back by `polysim log` (sim/log_inspect.h): every
// field of every line round-trips, and the log agrees with the run's summary.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "sim/log_inspect.h"
#include "sim/run.h"
#include "sim/step_log.h"
#include "sim/world.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

using nlohmann::json;

struct LoggedRun {
  json summary;
  std::vector<json> lines;
  std::string path;
};

// A tilted box landing on a corner and settling: events with point, line and area
// contacts, non-zero overlaps inside the band, several solver sweeps per step. Without
// speculative contacts, so that each touch as it rocks onto its face is an event of its
// own (with them, the box rocks onto its face within the steps, ending each touch at a
// zero gap, and the log holds one event).
const LoggedRun& tiltedDrop() {
  static const LoggedRun run = [] {
    LoggedRun r;
    r.path = ::polysim::test::tempPath("polysim_step_log_test.jsonl");
    RunOptions options;
    options.logPath = r.path;
    options.duration = 2.0;
    Scene scene = loadScene(std::string(POLYSIM_SCENES_DIR) + "/tilted_drop.json");
    scene.contact.speculativeReach = 0.0;
    r.summary = runScene(scene, options);
    std::ifstream in(r.path);
    for (std::string line; std::getline(in, line);) r.lines.push_back(json::parse(line));
    return r;
  }();
  return run;
}

json inspect(const LogQuery& query) {
  std::ostringstream out;
  inspectLog(tiltedDrop().path, query, out);
  return json::parse(out.str());
}

TEST(StepLog, EveryLineHoldsSpecFieldsAndTheLogAgreesWithTheSummary) {
  const LoggedRun& run = tiltedDrop();
  ASSERT_EQ(static_cast<long>(run.lines.size()), run.summary["steps"].get<long>());
  double deepest = 0.0;
  long events = 0;
  for (size_t k = 0; k < run.lines.size(); ++k) {
    const json& line = run.lines[k];
    EXPECT_EQ(line["step"].get<long>(), static_cast<long>(k + 1));
    for (const char* key : {"t", "events", "bodies", "energy", "penetration", "solver_iterations", "shock_sweeps"})
      ASSERT_TRUE(line.contains(key)) << "step " << k + 1 << " has no " << key;
    deepest = std::max(deepest, line["penetration"].get<double>());
    for (const json& e : line["events"]) {
      ++events;
      for (const char* key : {"time", "iterations", "stopped_by", "crossing", "pairs"}) ASSERT_TRUE(e.contains(key)) << key;
      // The pairs that crossed into each other are among the pairs in contact there.
      ASSERT_FALSE(e["crossing"].empty());
      for (const json& crossed : e["crossing"]) {
        bool listed = false;
        for (const json& p : e["pairs"])
          listed = listed || (crossed[0] == p["a"] && crossed[1] == p["b"]) || (crossed[0] == p["b"] && crossed[1] == p["a"]);
        EXPECT_TRUE(listed) << crossed.dump();
      }
      for (const json& p : e["pairs"])
        for (const json& c : p["contacts"]) {
          EXPECT_TRUE(c["type"] == "point" || c["type"] == "line" || c["type"] == "area") << c.dump();
          EXPECT_EQ(c["normal"].size(), 3u);
          // One gap per point, the separation the smallest of them.
          ASSERT_EQ(c["gaps"].size(), c["points"].size()) << c.dump();
          double smallest = c["gaps"][0].get<double>();
          for (const json& g : c["gaps"]) smallest = std::min(smallest, g.get<double>());
          EXPECT_EQ(c["separation"].get<double>(), smallest) << c.dump();
        }
    }
  }
  EXPECT_GT(events, 0);
  // The summary is made of the same steps: its deepest overlap, final energy and final
  // body states are the log's.
  EXPECT_GT(deepest, 0.0) << "the landing leaves overlaps inside the band";
  EXPECT_LE(deepest, 1e-4);
  EXPECT_DOUBLE_EQ(run.summary["max_penetration"].get<double>(), deepest);
  EXPECT_DOUBLE_EQ(run.summary["energy"]["final"].get<double>(), run.lines.back()["energy"].get<double>());
  EXPECT_EQ(run.summary["bodies"][0]["position"], run.lines.back()["bodies"][0]["position"]);
}

// `shock_sweeps` counts shock propagation's sweeps: every step of a 10-box stack whose
// solver may sweep 3 times (it stops at that limit, and the pass runs), none once the
// stack rests warm-started at the default limit (its sweeps converge).
TEST(StepLog, ShockSweepsAreCountedWhereTheSweepsStopAtTheirLimit) {
  auto lastSteps = [](int solverSweeps) {
    Scene scene = loadScene(std::string(POLYSIM_SCENES_DIR) + "/stack_10.json");
    scene.sleep.enabled = false;
    scene.contact.solverSweeps = solverSweeps;
    World w(scene);
    std::vector<int> shock;
    for (int k = 0; k < 60; ++k) shock.push_back(w.step(scene.dt).shockSweeps);
    return std::vector<int>(shock.end() - 10, shock.end());
  };
  for (int sweeps : lastSteps(3)) EXPECT_GT(sweeps, 0);
  for (int sweeps : lastSteps(dynamics::kSettlingSolverSweeps)) EXPECT_EQ(sweeps, 0);
}

TEST(StepLog, PolysimLogShowsEveryStepFieldAsWritten) {
  const LoggedRun& run = tiltedDrop();
  LogQuery query;
  query.body = "box";
  const json rows = inspect(query);
  ASSERT_EQ(rows.size(), run.lines.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const json &row = rows[k], &line = run.lines[k];
    SCOPED_TRACE("step " + std::to_string(k + 1));
    EXPECT_EQ(row["step"], line["step"]);
    EXPECT_EQ(row["t"], line["t"]);
    EXPECT_EQ(row["events"].get<size_t>(), line["events"].size());
    int tests = 0;
    for (const json& e : line["events"]) tests += e["iterations"].get<int>();
    EXPECT_EQ(row["toc_tests"].get<int>(), tests);
    EXPECT_EQ(row["penetration"], line["penetration"]);
    EXPECT_EQ(row["energy"], line["energy"]);
    EXPECT_EQ(row["solver_iterations"], line["solver_iterations"]);
    EXPECT_EQ(row["shock_sweeps"], line["shock_sweeps"]);
    EXPECT_EQ(row["position"], line["bodies"][0]["position"]);
    EXPECT_EQ(row["velocity"], line["bodies"][0]["velocity"]);
  }
}

TEST(StepLog, PolysimLogEventsAreTheLoggedEventsInOrder) {
  const LoggedRun& run = tiltedDrop();
  std::vector<json> logged;
  for (const json& line : run.lines)
    for (const json& e : line["events"]) logged.push_back(e);
  LogQuery query;
  query.events = true;
  const json rows = inspect(query);
  ASSERT_EQ(rows.size(), logged.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k]["time"], logged[k]["time"]);
    EXPECT_EQ(rows[k]["iterations"], logged[k]["iterations"]);
    EXPECT_EQ(rows[k]["stopped_by"], logged[k]["stopped_by"]);
    EXPECT_EQ(rows[k]["pairs"].get<std::string>().rfind("box/ground:", 0), 0u) << rows[k]["pairs"];
  }
}

TEST(StepLog, PolysimLogKeepsOnlyTheStepsInTheTimeWindow) {
  LogQuery query;
  query.from = 0.5;
  query.to = 1.0;
  const json rows = inspect(query);
  ASSERT_FALSE(rows.empty());
  for (const json& row : rows) {
    EXPECT_GE(row["t"].get<double>(), 0.5);
    EXPECT_LE(row["t"].get<double>(), 1.0);
  }
  EXPECT_EQ(rows.size(), 121u);  // steps ending at 0.5, 0.5 + 1/240, ..., 1.0 (the scene's dt 1/240)
}

// A box rattling at 10 m/s between two walls 1 mm apart, elastic, without gravity: a
// bounce every 0.1 ms, so every step of 1/60 s reaches the event bound. The summary
// counts those steps as the log marks them, and `polysim log` sums each step's tests.
TEST(StepLog, StepsAtTheEventBoundAreCountedAndTheirTestsSummed) {
  const std::string scenePath = ::polysim::test::tempPath("polysim_rattle.json");
  std::ofstream(scenePath) << R"({"name": "rattle", "gravity": [0, 0, 0], "dt": 0.016666666666666666,
    "contact": {"tolerance": 1e-4, "restitution": 1.0, "friction": 0.0},
    "bodies": [
      {"name": "left", "static": true, "shape": {"type": "box", "size": [1, 4, 4]}, "position": [-1.0005, 0, 0]},
      {"name": "right", "static": true, "shape": {"type": "box", "size": [1, 4, 4]}, "position": [1.0005, 0, 0]},
      {"name": "box", "shape": {"type": "box", "size": [1, 1, 1]}, "velocity": [10, 0, 0], "mass": 1.0}]})";
  const std::string logPath = ::polysim::test::tempPath("polysim_rattle.jsonl");
  RunOptions options;
  options.logPath = logPath;
  options.duration = 0.1;
  const json summary = runScene(loadScene(scenePath), options);
  std::vector<json> lines;
  std::ifstream in(logPath);
  for (std::string line; std::getline(in, line);) lines.push_back(json::parse(line));
  long marked = 0;
  for (const json& line : lines) marked += line.value("event_limit", false);
  EXPECT_EQ(marked, 6);  // every one of the 6 steps
  EXPECT_EQ(summary["event_limit_steps"].get<long>(), marked);
  EXPECT_NEAR(summary["energy"]["final"].get<double>(), 50.0, 1e-6);  // elastic: 0.5 m v^2 kept

  std::ostringstream out;
  inspectLog(logPath, {}, out);
  const json rows = json::parse(out.str());
  ASSERT_EQ(rows.size(), lines.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    int tests = 0;
    for (const json& e : lines[k]["events"]) tests += e["iterations"].get<int>();
    EXPECT_GE(lines[k]["events"].size(), 2u);
    EXPECT_EQ(rows[k]["toc_tests"].get<int>(), tests) << "step " << k + 1;
  }
}

// Two boxes dropped 5 m apart from 1 m and 3 m: two islands of one body each in every
// step, and each landing is an event of its own island, in the step where it lands
// (sqrt(2 h / g) after the start). `polysim log` shows the same per step.
TEST(StepLog, EachStepSaysHowManyIslandsSteppedAndTheirEvents) {
  const std::string scenePath = ::polysim::test::tempPath("polysim_two_drops.json");
  // Sleeping off: a box that has landed would leave the stepping islands 0.5 s later.
  std::ofstream(scenePath) << R"({"name": "two_drops", "gravity": [0, 0, -9.81], "dt": 0.016666666666666666,
    "sleep": {"enabled": false},
    "bodies": [
      {"name": "floor", "static": true, "shape": {"type": "box", "size": [20, 20, 1]}, "position": [0, 0, -0.5]},
      {"name": "low", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 1.5]},
      {"name": "high", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [5, 0, 3.5]}]})";
  const std::string logPath = ::polysim::test::tempPath("polysim_two_drops.jsonl");
  RunOptions options;
  options.logPath = logPath;
  options.duration = 1.0;
  runScene(loadScene(scenePath), options);
  std::vector<json> lines;
  std::ifstream in(logPath);
  for (std::string line; std::getline(in, line);) lines.push_back(json::parse(line));
  std::ostringstream out;
  inspectLog(logPath, {}, out);
  const json rows = json::parse(out.str());
  ASSERT_EQ(rows.size(), lines.size());
  const double dt = 1.0 / 60, g = 9.81;
  const long lowLands = static_cast<long>(std::ceil(std::sqrt(2 * 1.0 / g) / dt));
  const long highLands = static_cast<long>(std::ceil(std::sqrt(2 * 3.0 / g) / dt));
  for (size_t k = 0; k < lines.size(); ++k) {
    const long step = static_cast<long>(k + 1);
    const json& line = lines[k];
    EXPECT_EQ(line["island_bodies"], json::array({1, 1})) << "step " << step;
    ASSERT_EQ(line["island_events"].size(), 2u);
    const int events = line["island_events"][0].get<int>() + line["island_events"][1].get<int>();
    EXPECT_EQ(events, static_cast<int>(line["events"].size())) << "step " << step;
    EXPECT_EQ(events, (step == lowLands) + (step == highLands)) << "step " << step;
    EXPECT_EQ(rows[k]["islands"].get<int>(), 2);
    EXPECT_EQ(rows[k]["island_events"], line["island_events"]);
  }
}

// A figure missing from a line is shown as missing, not as a plausible zero.
TEST(StepLog, PolysimLogShowsAMissingFigureAsNull) {
  const std::string path = ::polysim::test::tempPath("polysim_step_log_missing.jsonl");
  std::ofstream(path) << R"({"step":1,"t":0.1,"events":[],"bodies":[],"energy":2.5})" << "\n";
  std::ostringstream out;
  inspectLog(path, {}, out);
  const json rows = json::parse(out.str());
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0]["penetration"].is_null());
  EXPECT_TRUE(rows[0]["solver_iterations"].is_null());
  EXPECT_TRUE(rows[0]["shock_sweeps"].is_null());
  EXPECT_EQ(rows[0]["energy"].get<double>(), 2.5);
}

TEST(StepLog, PolysimLogRejectsALineThatIsNotAStepNamingTheLine) {
  const std::string path = ::polysim::test::tempPath("polysim_step_log_bad.jsonl");
  std::ofstream(path) << R"({"step":1,"t":0.1,"events":[],"bodies":[],"energy":2.5})" << "\n"
                      << "not json\n"
                      << R"({"step":3,"t":0.3,"events":[],"bodies":[],"energy":2.5})" << "\n";
  std::ostringstream out;
  try {
    inspectLog(path, {}, out);
    FAIL() << "a garbage line in the middle of a log must be an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + " line 2"), std::string::npos) << e.what();
  }
}

// The same scene twice gives byte-identical step lines.
TEST(StepLog, SameSceneTwiceGivesAnIdenticalLog) {
  auto logOf = [](const std::string& name) {
    World w(loadScene(std::string(POLYSIM_SCENES_DIR) + "/" + name + ".json"));
    std::string all;
    for (long k = 0; k < std::lround(1.0 / w.scene().dt); ++k) all += stepToJson(w, w.step(w.scene().dt)).dump() + "\n";
    return all;
  };
  EXPECT_EQ(logOf("tilted_drop"), logOf("tilted_drop"));
  EXPECT_EQ(logOf("pyramid"), logOf("pyramid"));
}

TEST(StepLog, EveryLineIsACompleteStepWithItsEvents) {
  const std::string path = ::polysim::test::tempPath("polysim_bounce.jsonl");
  RunOptions options;
  options.logPath = path;
  options.duration = 1.0;
  const nlohmann::ordered_json summary = runScene(loadScene(std::string(POLYSIM_SCENES_DIR) + "/bounce.json"), options);
  std::ifstream in(path);
  std::string line;
  long lines = 0, events = 0;
  while (std::getline(in, line)) {
    const auto j = nlohmann::json::parse(line);
    ++lines;
    ASSERT_EQ(j["step"].get<long>(), lines);
    ASSERT_TRUE(j.contains("t") && j.contains("bodies") && j.contains("energy"));
    events += static_cast<long>(j["events"].size());
  }
  EXPECT_EQ(lines, summary["steps"].get<long>());
  EXPECT_GE(events, 2);  // the landing and at least one rebound
}

}  // namespace
}  // namespace polysim::sim
