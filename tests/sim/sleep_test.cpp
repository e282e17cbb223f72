// Sleeping (dynamics/sleep.h, World): an island whose bodies have all been slow for the
// scene's sleep time stops costing anything and keeps its poses exactly, until a body
// that moves can reach it. Checked on hand-built scenes against the fall time and the
// rest heights, on a slow slide that must not be put to sleep, and on seeded piles and
// a column of non-convex cups with their invariants.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "sim/log_inspect.h"
#include "sim/run.h"
#include "sim/scene.h"
#include "sim/scene_generators.h"
#include "sim/world.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

constexpr double g = 9.81;
constexpr double kDt = 1.0 / 60;

Scene sceneFrom(const std::string& name, const std::string& text) {
  const std::string path = ::polysim::test::tempPath("polysim_sleep_" + name + ".json");
  std::ofstream(path) << text;
  return loadScene(path);
}

// A ground and unit boxes at the given centres (x, z), dt 1/60.
Scene boxes(const std::string& name, const std::vector<std::pair<double, double>>& centres) {
  std::ostringstream s;
  s << R"({"name": ")" << name << R"(", "dt": )" << kDt << R"(, "bodies": [
    {"name": "ground", "static": true, "shape": {"type": "box", "size": [20, 20, 1]}, "position": [0, 0, -0.5]})";
  for (size_t k = 0; k < centres.size(); ++k)
    s << R"(, {"name": "box)" << k << R"(", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [)"
      << centres[k].first << ", 0, " << centres[k].second << "]}";
  s << "]}";
  return sceneFrom(name, s.str());
}

Scene generated(const std::string& kind, int count, unsigned long long seed) {
  MakeOptions o;
  o.kind = kind;
  o.count = count;
  o.seed = seed;
  return sceneFrom(kind + std::to_string(seed), makeScene(o).dump());
}

bool samePose(const dynamics::RigidBody& a, const dynamics::RigidBody& b) {
  return a.position == b.position && a.orientation.coeffs() == b.orientation.coeffs();
}

// A step that costs nothing: no island stepped, no solver sweep, no event.
void expectIdle(const StepReport& r) {
  EXPECT_TRUE(r.islands.empty()) << "step " << r.step;
  EXPECT_EQ(r.solverIterations, 0) << "step " << r.step;
  EXPECT_TRUE(r.events.empty()) << "step " << r.step;
}

// A box dropped from 1 m lands at sqrt(2 h / g), rests, and falls asleep the sleep time
// later; from then on its pose is exactly what it was and a step does no work.
TEST(Sleep, ALandedBoxFallsAsleepAfterTheSleepTimeAndKeepsItsPoseExactly) {
  World w(boxes("drop", {{0.0, 1.5}}));
  const double lands = std::sqrt(2 * 1.0 / g);
  double fellAsleep = -1.0;
  while (fellAsleep < 0 && w.time() < 3.0) {
    const StepReport& r = w.step(kDt);
    if (!r.fellAsleep.empty()) fellAsleep = r.time;
    EXPECT_TRUE(r.woke.empty());
  }
  ASSERT_GT(fellAsleep, 0.0) << "never fell asleep";
  // Slow from the step it lands in: asleep sleep-time later, give or take that step.
  EXPECT_GE(fellAsleep, lands + w.scene().sleep.time - kDt);
  EXPECT_LE(fellAsleep, lands + w.scene().sleep.time + 2 * kDt);
  ASSERT_TRUE(w.asleep(1));
  const dynamics::RigidBody asleep = w.bodies()[1];
  EXPECT_NEAR(asleep.position.z(), 0.5, w.scene().contact.tolerance);
  EXPECT_TRUE(asleep.velocity.isZero(0.0) && asleep.angularVelocity.isZero(0.0));
  for (int k = 0; k < 120; ++k) {
    const StepReport& r = w.step(kDt);
    expectIdle(r);
    EXPECT_EQ(r.sleeping, 1);
    EXPECT_TRUE(samePose(w.bodies()[1], asleep)) << "step " << r.step;
  }
  EXPECT_TRUE(w.atRest(1));
  EXPECT_EQ(w.contacts().size(), 1u);  // it still lies on the ground
}

TEST(Sleep, NothingSleepsWhenTheSceneTurnsItOff) {
  Scene s = boxes("drop_awake", {{0.0, 1.5}});
  s.sleep.enabled = false;
  World w(s);
  for (int k = 0; k < 180; ++k) {
    const StepReport& r = w.step(kDt);
    EXPECT_EQ(r.sleeping, 0);
    EXPECT_EQ(r.islands.size(), 1u);  // the box's island steps every step
  }
  EXPECT_FALSE(w.asleep(1));
}

// A stack of 3 falls asleep; a box dropped 8 m onto it wakes it before it lands, lands
// at the fall time, and the four come to rest, one on another, and sleep again. While
// asleep, the stack's poses do not change by a bit.
TEST(Sleep, AFallingBoxWakesASleepingStackAndAllSleepAgainAtTheirRestHeights) {
  World w(boxes("wake", {{0.0, 0.5}, {0.0, 1.5}, {0.0, 2.5}, {0.0, 11.5}}));
  const double eps = w.scene().contact.tolerance;
  const double lands = std::sqrt(2 * 8.0 / g), initial = w.energy();
  double bound = 0.0;  // SPEC.md's energy bound: every body lifted by one tolerance
  for (const dynamics::RigidBody& b : w.bodies()) bound += b.mass * g * eps;
  std::map<int, dynamics::RigidBody> sleptAt;
  std::vector<double> wokeAt(5, -1.0);
  double touched = -1.0;
  while (w.time() < 4.0) {
    const StepReport& r = w.step(kDt);
    EXPECT_LE(r.penetration, eps) << "step " << r.step;
    EXPECT_LE(w.energy() - initial, bound) << "step " << r.step;
    for (int i : r.fellAsleep) sleptAt[i] = w.bodies()[static_cast<size_t>(i)];
    for (int i : r.woke) {
      sleptAt.erase(i);
      if (wokeAt[static_cast<size_t>(i)] < 0) wokeAt[static_cast<size_t>(i)] = r.time;
    }
    for (const auto& [i, pose] : sleptAt) EXPECT_TRUE(samePose(w.bodies()[static_cast<size_t>(i)], pose)) << "box" << i - 1;
    for (const collision::PairResult& p : w.contacts())
      if (touched < 0 && p.a + p.b == 3 + 4) touched = r.time;  // box2 and box3
    if (r.time > 1.0 && r.time < 1.0 + kDt / 2) {
      EXPECT_EQ(r.sleeping, 3) << "the stack sleeps while the box falls";
    }
  }
  EXPECT_NEAR(touched, lands, kDt + 1e-9);
  for (int i = 1; i <= 3; ++i) {
    EXPECT_GT(wokeAt[static_cast<size_t>(i)], lands - 2 * kDt) << "box" << i - 1 << " woke too early";
    EXPECT_LE(wokeAt[static_cast<size_t>(i)], touched) << "box" << i - 1 << " woke only after it was hit";
  }
  for (int i = 1; i <= 4; ++i) {
    const dynamics::RigidBody& b = w.bodies()[static_cast<size_t>(i)];
    EXPECT_TRUE(w.asleep(i)) << "box" << i - 1;
    EXPECT_NEAR(b.position.z(), 0.5 + (i - 1), i * eps) << "box" << i - 1;
    EXPECT_LT(b.position.head<2>().norm(), 1e-6) << "box" << i - 1;
  }
}

// A box asleep on the ground is woken by a frictionless box sliding past 1 cm away (their
// islands meet), which never touches it. Woken, it rests through that step: no gravity
// and no path, so its pose does not change by a bit and the step has no event (given a
// fall, it would sink into the ground within the step and be backed up to).
TEST(Sleep, ABodyWokenByOneThatPassesByKeepsItsPoseThroughTheStepItWakes) {
  World w(sceneFrom("pass_by", R"({"name": "pass_by", "dt": 0.016666666666666666, "bodies": [
    {"name": "ground", "static": true, "shape": {"type": "box", "size": [20, 20, 1]}, "position": [0, 0, -0.5]},
    {"name": "sleeper", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 0.5]},
    {"name": "slider", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [-8, 1.01, 0.5],
     "velocity": [2, 0, 0], "friction": 0.0}]})"));
  bool woken = false;
  while (!woken && w.time() < 6.0) {
    const dynamics::RigidBody before = w.bodies()[1];
    const bool wasAsleep = w.asleep(1);
    const StepReport& r = w.step(kDt);
    if (!wasAsleep || std::find(r.woke.begin(), r.woke.end(), 1) == r.woke.end()) continue;
    woken = true;
    EXPECT_LT(std::abs(w.bodies()[2].position.x()), 1.5) << "woken before the slider came near";
    EXPECT_TRUE(samePose(w.bodies()[1], before)) << "moved by " << (w.bodies()[1].position - before.position).norm() << " m";
    EXPECT_TRUE(r.events.empty()) << r.events.size() << " events in the step it woke";
  }
  EXPECT_TRUE(woken) << "the sleeper was never asleep and woken by the slider";
}

// A box sliding from rest down a 30 degree ramp with friction 0.5656 accelerates at
// g (sin - mu cos) = 0.1 m/s^2: slow for its first 0.1 s, never slow for the sleep time.
// It must not be put to sleep, and it slides as Coulomb says.
TEST(Sleep, ASlowSlideFromRestIsNotPutToSleep) {
  Scene s = loadScene(std::string(POLYSIM_SCENES_DIR) + "/ramp_slides.json");
  const double angle = M_PI / 6, mu = 0.5656;
  s.contact.friction = mu;
  World w(s);
  const dynamics::RigidBody start = w.bodies()[1];
  const double seconds = 3.0;
  for (long k = 0; k < std::lround(seconds / s.dt); ++k) EXPECT_EQ(w.step(s.dt).sleeping, 0);
  const double a = g * (std::sin(angle) - mu * std::cos(angle));
  const double expected = 0.5 * a * seconds * seconds;
  EXPECT_NEAR((w.bodies()[1].position - start.position).norm(), expected, 0.02 * expected);
}

// Seeded tilted piles (other seeds than the busy-scene tests) and a column of cups, with
// sleeping on: the invariants hold, no sleeping body moves by a bit, everything is
// asleep by the end, and a step then costs nothing.
TEST(Sleep, SeededPilesAndCupsFallAsleepWithTheirInvariants) {
  struct Case {
    std::string kind;
    int count;
    unsigned long long seed;
    double seconds;
  };
  for (const Case& c : {Case{"pile", 27, 4, 8.0}, Case{"pile", 20, 5, 8.0}, Case{"cups", 5, 6, 10.0}}) {
    SCOPED_TRACE(c.kind + " seed " + std::to_string(c.seed));
    World w(generated(c.kind, c.count, c.seed));
    const double eps = w.scene().contact.tolerance, initial = w.energy();
    double bound = 0.0;
    for (const dynamics::RigidBody& b : w.bodies()) bound += b.mass * g * eps;
    std::map<int, dynamics::RigidBody> sleptAt;
    double rise = 0.0, deepest = 0.0;
    bool finite = true, moved = false;
    for (long k = 0; k < std::lround(c.seconds / w.scene().dt); ++k) {
      const StepReport& r = w.step(w.scene().dt);
      rise = std::max(rise, w.energy() - initial);
      deepest = std::max(deepest, r.penetration);
      for (int i : r.woke) sleptAt.erase(i);
      for (int i : r.fellAsleep) sleptAt[i] = w.bodies()[static_cast<size_t>(i)];
      for (const auto& [i, pose] : sleptAt) moved = moved || !samePose(w.bodies()[static_cast<size_t>(i)], pose);
      for (const dynamics::RigidBody& b : w.bodies()) finite = finite && b.position.allFinite() && b.velocity.allFinite();
    }
    EXPECT_TRUE(finite);
    EXPECT_FALSE(moved) << "a sleeping body moved";
    EXPECT_LE(rise, bound);
    EXPECT_LE(deepest, eps);
    int dynamic = 0;
    for (const dynamics::RigidBody& b : w.bodies()) dynamic += !b.isStatic;
    ASSERT_EQ(w.step(w.scene().dt).sleeping, dynamic);
    expectIdle(w.step(w.scene().dt));
  }
}

// A box sliding on the ground stops within the tolerance of a box at rest: the two are
// in contact, so they must share an island and the contact must be reported, though
// neither container, grown by how far its body can move, reaches the other. Where it
// stops is taken from a run without the second box (the runs agree up to the last step).
TEST(Sleep, ABoxThatStopsWithinTheToleranceOfAnotherIsInContactWithIt) {
  const std::string slide = R"({"name": "slide", "dt": 0.016666666666666666, "gravity": [0, 0, -9.81], "bodies": [
    {"name": "ground", "static": true, "shape": {"type": "box", "size": [40, 20, 1]}, "position": [0, 0, -0.5]},
    {"name": "slider", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 0.5], "velocity": [2, 0, 0]})";
  World alone(sceneFrom("slide_alone", slide + "]}"));
  for (int k = 0; k < 120; ++k) alone.step(kDt);
  ASSERT_TRUE(alone.asleep(1) || alone.atRest(1));
  const double stop = alone.bodies()[1].position.x(), eps = alone.scene().contact.tolerance;
  std::ostringstream wall;
  wall.precision(17);
  wall << R"(, {"name": "resting", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [)" << stop + 1 + 0.5 * eps
       << ", 0, 0.5]}]}";
  World w(sceneFrom("slide_to_rest", slide + wall.str()));
  for (int k = 0; k < 120; ++k) w.step(kDt);
  EXPECT_NEAR(w.bodies()[1].position.x(), stop, 1e-9);
  bool touching = false;
  for (const collision::PairResult& p : w.contacts()) touching = touching || (p.a == 1 && p.b == 2);
  EXPECT_TRUE(touching) << "the slider stopped " << 0.5 * eps << " m from the box and no contact was reported";
}

// The step log names who falls asleep and who wakes, and counts the sleepers; `polysim
// log` shows the count.
TEST(Sleep, TheStepLogSaysWhoSleepsAndWakes) {
  const std::string scenePath = ::polysim::test::tempPath("polysim_sleep_log.json");
  std::ofstream(scenePath) << R"({"name": "sleep_log", "dt": 0.016666666666666666, "bodies": [
    {"name": "ground", "static": true, "shape": {"type": "box", "size": [20, 20, 1]}, "position": [0, 0, -0.5]},
    {"name": "bottom", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 0.5]},
    {"name": "dropped", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 6.5]}]})";
  const std::string logPath = ::polysim::test::tempPath("polysim_sleep_log.jsonl");
  RunOptions options;
  options.logPath = logPath;
  options.duration = 3.0;
  const nlohmann::ordered_json summary = runScene(loadScene(scenePath), options);
  EXPECT_EQ(summary["sleeping_bodies"], 2);
  std::vector<nlohmann::json> lines;
  std::ifstream in(logPath);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  std::vector<std::string> sequence;  // "name fell asleep" / "name woke", in order
  for (const nlohmann::json& line : lines) {
    for (const auto& name : line.value("fell_asleep", nlohmann::json::array())) sequence.push_back(name.get<std::string>() + " slept");
    for (const auto& name : line.value("woke", nlohmann::json::array())) sequence.push_back(name.get<std::string>() + " woke");
  }
  const std::vector<std::string> expected = {"bottom slept", "bottom woke", "bottom slept", "dropped slept"};
  EXPECT_EQ(sequence, expected);
  std::ostringstream out;
  inspectLog(logPath, {}, out);
  const nlohmann::json rows = nlohmann::json::parse(out.str());
  ASSERT_EQ(rows.size(), lines.size());
  for (size_t k = 0; k < lines.size(); ++k) EXPECT_EQ(rows[k]["sleeping"], lines[k]["sleeping"]);
  EXPECT_EQ(rows.back()["sleeping"], 2);
}

}  // namespace
}  // namespace polysim::sim
