// The bound on contact events in a step (kMaxEventsPerStep) is per body: it stops a box
// bouncing ever lower, not an island in which many bodies each land once.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "sim/world.h"
#include "tests/sim/scenario_support.h"

namespace polysim::sim {
namespace {

using test::g;

// A row of 12 unit boxes resting side by side on the floor, each sunk half a tolerance
// into its neighbour (one island, by their contacts), and a box of 0.8 m above each (not
// touching its neighbours, so flying free: a body in contact would meet the row through
// speculative contacts, with no event), its bottom d_k = 0.27 m + k mm above the row:
// they land at sqrt(2 d_k / g), 0.44 ms apart, all within one step of 1/60 s and all in
// the row's island. Each landing is its own event at its own time; no step reaches the
// bound (an island's bound of 8 would stop the island's clock at the eighth, and the
// last boxes would land a step late).
TEST(EventBound, TwelveBoxesLandingOnOneIslandInOneStepEachLandOnTime) {
  constexpr int kRow = 12;
  constexpr double eps = 1e-4;
  std::string bodies = R"({"name": "floor", "static": true, "shape": {"type": "box", "size": [40, 10, 1]}, "position": [0, 0, -0.5]})";
  for (int k = 0; k < kRow; ++k) {
    const double x = k * (1.0 - 0.5 * eps);
    bodies += R"(, {"name": "row)" + std::to_string(k) + R"(", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [)" +
              std::to_string(x) + ", 0, 0.5]}";
    const double drop = 0.27 + 1e-3 * k;
    bodies += R"(, {"name": "drop)" + std::to_string(k) + R"(", "shape": {"type": "box", "size": [0.8, 0.8, 0.8]}, "position": [)" +
              std::to_string(x) + ", 0, " + std::to_string(1.4 + drop) + "]}";
  }
  const std::string path = ::polysim::test::tempPath("event_bound_row.json");
  std::ofstream(path) << R"({"dt": 0.016666666666666666, "duration": 0.5, "contact": {"tolerance": 0.0001},)"
                      << R"( "sleep": {"enabled": false}, "bodies": [)" << bodies << "]}\n";
  World w(loadScene(path));
  std::vector<double> landing(w.bodies().size(), -1.0);
  int mostIslandEvents = 0;
  while (w.time() < 0.5 - 1e-9) {
    const StepReport& r = w.step(w.scene().dt);
    EXPECT_FALSE(r.eventLimitHit) << "step " << r.step;
    for (const IslandReport& island : r.islands) mostIslandEvents = std::max(mostIslandEvents, island.events);
    for (const StepEvent& e : r.events)
      for (const auto& [a, b] : e.toc.crossing)
        for (int i : {a, b})
          if (landing[i] < 0.0) landing[i] = e.time;
  }
  EXPECT_GE(mostIslandEvents, kRow);
  for (int k = 0; k < kRow; ++k) {
    const int drop = test::bodyIndex(w, "drop" + std::to_string(k));
    const double d = 0.27 + 1e-3 * k;
    const double speed = std::sqrt(2 * g * d);
    SCOPED_TRACE("drop" + std::to_string(k));
    // Just contact: the gap within the band, so the time within 2 eps over the speed.
    EXPECT_NEAR(landing[drop], std::sqrt(2 * d / g), 2 * eps / speed);
  }
}

// A unit box dropped onto a floor with restitution 0.7, landing at 8 m/s, in steps of
// `dt` seconds: a file of the scene.
std::string bouncingBox(double dt) {
  const double v0 = 8.0, drop = v0 * v0 / (2 * g);
  const std::string path = ::polysim::test::tempPath("event_bound_bounce.json");
  std::ofstream(path) << R"({"dt": )" << dt << R"(, "duration": 40, "contact": {"tolerance": 0.0001, "restitution": 0.7,)"
                      << R"( "friction": 0}, "sleep": {"enabled": false}, "bodies": [)"
                      << R"({"name": "floor", "static": true, "shape": {"type": "box", "size": [10, 10, 1]}, "position": [0, 0, -0.5]},)"
                      << R"({"name": "box", "mass": 1, "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, )" << 0.5 + drop
                      << "]}]}\n";
  return path;
}

// In one step of 10 s the box lands and bounces seven times, at 8 m/s and then 0.7 times
// the speed each time (its flights 2 v / g), all above the bounce threshold: the eighth
// landing, at 0.66 m/s, is its eighth event, and its island's clock stops there, the box
// at the floor with the speed it landed at. Nothing is given for the time it did not fly:
// its energy is that of the eighth landing to within the band. The next step starts with
// that landing and bounces it; from then on the energy never rises.
TEST(EventBound, ABoxBouncingEightTimesInOneStepStopsAtTheEighthLanding) {
  constexpr double eps = 1e-4, v0 = 8.0, e = 0.7;
  World w(loadScene(bouncingBox(10.0)));
  const int box = test::bodyIndex(w, "box");
  const StepReport& first = w.step(w.scene().dt);
  EXPECT_TRUE(first.eventLimitHit);
  ASSERT_EQ(first.events.size(), 8u);
  double landing = v0 / g, speed = v0;  // the first landing's time (s) and speed (m/s)
  for (int k = 0; k < 8; ++k) {
    SCOPED_TRACE("landing " + std::to_string(k));
    EXPECT_NEAR(first.events[k].time, landing, 1e-3);  // each within eps of the floor: a few eps over the speed, summed
    landing += 2 * e * speed / g;
    speed *= e;
  }
  const double landed = v0 * std::pow(e, 7);  // the eighth landing's speed
  EXPECT_NEAR(w.bodies()[box].velocity.z(), -landed, 1e-3);  // each landing a few eps short of the floor
  EXPECT_NEAR(w.energy(), 0.5 * landed * landed + g * 0.5, g * eps);
  double last = w.energy();
  for (int step = 0; step < 3; ++step) {
    w.step(w.scene().dt);
    EXPECT_LE(w.energy(), last + g * eps) << "step " << step + 2;
    last = w.energy();
  }
}

// The same box in steps of 0.5 to 2 s: a box that has just bounced is still within the
// band when the next step starts. Given the whole step's gravity there (a supported
// body's semi-implicit step), it approached the floor at up to g dt and bounced off
// that too: at dt 1 s it gained 12 J, at 2 s 200 J (and 29 J at 2 s before the bounce
// of an event was judged before its solve). Its energy never rises, and it comes to rest.
TEST(EventBound, ABoxBouncingInLongStepsNeverGainsEnergy) {
  constexpr double eps = 1e-4;
  for (double dt : {0.5, 1.0, 2.0}) {
    SCOPED_TRACE("dt " + std::to_string(dt));
    World w(loadScene(bouncingBox(dt)));
    const double start = w.energy();
    double highest = start;
    for (int step = 0; step * dt < 20.0; ++step) {
      w.step(dt);
      highest = std::max(highest, w.energy());
    }
    EXPECT_LE(highest, start + g * eps);
    EXPECT_TRUE(w.atRest(test::bodyIndex(w, "box")));
  }
}

// An event tests again the groups of pairs that came within the band without contacts
// (TocResult::nearing), not only the group of the pair that caused it. Box "fast" is
// thrown down and lands at about t = 0.01 s; box "slow", 1 cm beside it (one island),
// is let go from rest 5.4 bands above the floor, so at that time gravity has taken it to
// half a band above the floor, and it would interpenetrate at 0.0114 s. Its pair with
// the floor is tested at the landing's event and solved there: the step has that one
// event, whose pairs hold both boxes' contacts with the floor. Found only once it
// interpenetrated, its landing would be an event of its own.
TEST(EventBound, AnEventTestsThePairsThatCameWithinTheBandElsewhereInItsIsland) {
  constexpr double eps = 1e-4;
  const double tLand = 0.01, speed = 1.0;
  const double fastGap = speed * tLand + 0.5 * g * tLand * tLand;
  const double slowGap = 0.5 * g * tLand * tLand + 0.5 * eps;
  const std::string path = ::polysim::test::tempPath("event_nearing.json");
  std::ofstream(path) << R"({"dt": 0.016666666666666666, "duration": 0.1, "contact": {"tolerance": 0.0001},)"
                      << R"( "sleep": {"enabled": false}, "bodies": [)"
                      << R"({"name": "floor", "static": true, "shape": {"type": "box", "size": [10, 10, 1]}, "position": [0, 0, -0.5]},)"
                      << R"( {"name": "fast", "shape": {"type": "box", "size": [1, 1, 1]}, "velocity": [0, 0, -1], "position": [0, 0, )"
                      << std::to_string(0.5 + fastGap) << "]},"
                      << R"( {"name": "slow", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [1.01, 0, )"
                      << std::to_string(0.5 + slowGap) << "]}]}\n";
  World w(loadScene(path));
  const int floor = test::bodyIndex(w, "floor"), fast = test::bodyIndex(w, "fast"), slow = test::bodyIndex(w, "slow");
  const StepReport& r = w.step(w.scene().dt);
  ASSERT_EQ(r.islands.size(), 1u) << "the two boxes step as one island";
  ASSERT_EQ(r.events.size(), 1u) << "the slow box's landing was an event of its own";
  const StepEvent& e = r.events[0];
  EXPECT_NEAR(e.time, tLand, 2 * eps / speed);
  EXPECT_EQ(e.toc.crossing, (std::vector<std::pair<int, int>>{bodyPair(floor, fast)}));
  BodyPairs tested;
  for (const collision::PairResult& p : e.toc.pairs)
    if (!p.contacts.empty()) tested.insert(bodyPair(p.a, p.b));
  EXPECT_EQ(tested, (BodyPairs{bodyPair(floor, fast), bodyPair(floor, slow)}));
  EXPECT_GE(w.bodies()[slow].position.z(), 0.5 - eps) << "the slow box is held by the floor";
}

}  // namespace
}  // namespace polysim::sim
