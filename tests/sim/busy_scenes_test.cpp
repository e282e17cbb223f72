// The busy scenes (piles of tilted boxes, tall stacks, columns of cups), generated as
// `polysim make` writes them (scene_generators.h) and run with their invariants: the
// energy bound (total energy never rises more than the sum over bodies of m g eps), no
// overlap deeper than eps at any committed state, nothing NaN, nothing out of its pen,
// every body at rest by the end.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "sim/scene.h"
#include "sim/world.h"
#include "tests/sim/scenario_support.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

using test::generated;

// What a run kept true, step by step.
struct Watched {
  double energyRise = 0.0;  // J, largest rise over the initial energy
  double deepest = 0.0;     // m, deepest overlap of a committed state
  bool finite = true;
  /// Steps in which an island's clock stood still: all its events, up to the bound, at
  /// the step's start (the detector and the solver disagreeing about one pair).
  int stalledSteps = 0;
  /// Steps in which an island reached the event bound at all.
  int boundSteps = 0;
  /// Steps that ended interpenetrating by a fresh test (no reuse, nothing kept).
  int interpenetratingSteps = 0;
};

// An island of the step reached the event bound without its clock moving.
bool stalled(const StepReport& r, double stepStart) {
  size_t first = 0;
  for (const IslandReport& island : r.islands) {
    const auto begin = r.events.begin() + static_cast<long>(first);
    first += static_cast<size_t>(island.events);
    if (island.events < kMaxEventsPerStep) continue;
    if (std::all_of(begin, begin + island.events, [&](const StepEvent& e) { return e.time == stepStart; })) return true;
  }
  return false;
}

// Every `freshEvery` steps the state is also judged by a fresh test (0.3 s a test for
// the 820-box pyramid, whose pairs are all in contact and none reused).
Watched run(World& w, double seconds, int freshEvery = 1) {
  Watched seen;
  const double initial = w.energy();
  const long steps = std::lround(seconds / w.scene().dt);
  test::FreshVerdict fresh(w.scene());
  for (long k = 0; k < steps; ++k) {
    const double stepStart = w.time();
    const StepReport& r = w.step(w.scene().dt);
    if (k % freshEvery == freshEvery - 1) seen.interpenetratingSteps += fresh.interpenetrating(w);
    seen.stalledSteps += stalled(r, stepStart);
    seen.boundSteps += r.eventLimitHit;
    seen.energyRise = std::max(seen.energyRise, w.energy() - initial);
    seen.deepest = std::max(seen.deepest, r.penetration);
    for (const dynamics::RigidBody& b : w.bodies())
      seen.finite = seen.finite && b.position.allFinite() && b.velocity.allFinite() && b.angularVelocity.allFinite();
  }
  return seen;
}

// Lifting every dynamic body by one tolerance: SPEC.md's energy bound.
double energyBound(const World& w) {
  double bound = 0.0;
  for (const dynamics::RigidBody& b : w.bodies()) bound += b.mass * w.scene().gravity.norm() * w.scene().contact.tolerance;
  return bound;
}

void expectInvariants(const World& w, const Watched& seen) {
  EXPECT_TRUE(seen.finite);
  EXPECT_LE(seen.energyRise, energyBound(w));
  EXPECT_LE(seen.deepest, w.scene().contact.tolerance);
  EXPECT_EQ(seen.interpenetratingSteps, 0);
  for (size_t i = 0; i < w.bodies().size(); ++i) EXPECT_TRUE(w.atRest(static_cast<int>(i))) << w.scene().bodies[i].name;
}

// 27 unit boxes, each tilted by up to 0.3 rad, dropped 1.5 m apart into the 16 m pen:
// they land on corners and edges, many in the same steps, and topple onto each other.
// Both time-of-contact methods: regula falsi once returned the state it began from when
// a box rocked onto its next corner, and its island's clock stood still from then on.
TEST(BusyScenes, TiltedPilesKeepTheEnergyBoundAndComeToRest) {
  for (collision::TocMethod method : {collision::TocMethod::Bisection, collision::TocMethod::RegulaFalsi}) {
    for (unsigned long long seed : {1ull, 2ull}) {
      SCOPED_TRACE(collision::toString(method) + ", seed " + std::to_string(seed));
      World w(generated("pile", 27, seed), method);
      const Watched seen = run(w, 6.0);
      expectInvariants(w, seen);
      EXPECT_EQ(seen.stalledSteps, 0);
      for (const dynamics::RigidBody& b : w.bodies()) {
        if (b.isStatic) continue;
        EXPECT_LT(b.position.head<2>().cwiseAbs().maxCoeff(), 8.0);  // inside the pen
        EXPECT_GT(b.position.z(), 0.0);
      }
    }
  }
}

// Nine ten-box columns of the tilted pile of 1000 (box K = i + 10 j + 100 layer, i and j in
// [first, first + 3)), with the ground and walls.
Scene columnsOfThePile(unsigned long long seed, int first) {
  Scene columns = generated("pile", 1000, seed);
  const auto outside = [first](const BodySpec& b) {
    if (b.isStatic) return false;
    const int k = std::stoi(b.name.substr(3));
    const int i = k % 10, j = k / 10 % 10;
    return i < first || i >= first + 3 || j < first || j >= first + 3;
  };
  columns.bodies.erase(std::remove_if(columns.bodies.begin(), columns.bodies.end(), outside), columns.bodies.end());
  return columns;
}

// The middle nine columns of the tilted pile of 1000: ten boxes each, every one tilted by
// up to 0.3 rad, landing on one another and leaning on the next column. Their bodies
// hover about the speed that marks a body still, which turns the order their pairs come
// in; the warm start must follow the pair either way (warm_start.h). When it did not,
// seeds 4, 8 and 10 of 10 still moved at 8 s (at up to 8 cm/s; seed 8 74 of 90 at rest),
// and towers crept sideways in the full pile for good. Since, every seed of 16 rests by
// 4.9 s, at under 1e-7 m/s. Without sleeping, so rest is the solver's, not a threshold's.
// Seed 15 crept at 3 mm/s at 8 s at a settling limit of 200 (kSettlingSolverSweeps).
TEST(BusyScenes, TiltedTowersOfTenComeToRest) {
  for (unsigned long long seed : {1ull, 2ull, 3ull, 4ull, 5ull, 6ull, 7ull, 8ull, 15ull}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    World w(columnsOfThePile(seed, 3));
    ASSERT_EQ(w.bodies().size(), 95u);  // ground, four walls, 90 boxes
    const Watched seen = run(w, 8.0);
    expectInvariants(w, seen);
  }
}

// The same towers in the pen's corner, their tops leaning on the walls. Shock propagation
// once ranked a column from a wall down as well as from the ground up (shock_propagation.h),
// and bridged columns stopped at 60 sweeps at 1 to 3 cm/s (kSettlingSolverSweeps). Then
// seed 1 still moved at 8 s and seed 2 rested at 7.1 s; now seeds 1 to 8 rest by 4.4 s.
TEST(BusyScenes, TiltedTowersInTheCornerComeToRest) {
  for (unsigned long long seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    World w(columnsOfThePile(seed, 0));
    ASSERT_EQ(w.bodies().size(), 95u);
    const Watched seen = run(w, 6.0);
    expectInvariants(w, seen);
  }
}

// A column of 6 open cups (non-convex) dropped 0.2 m onto each other: each lands in the
// one below and the column settles.
TEST(BusyScenes, ColumnOfCupsKeepsTheEnergyBoundAndComesToRest) {
  World w(generated("cups", 6));
  const Watched seen = run(w, 10.0);
  expectInvariants(w, seen);
}

// The column: 20 cups, each up to 5 cm off the column's axis, dropped 0.2 m onto
// each other, for 20 s. Each lands a little tilted and rests on one corner of the rim
// below; the sweeps, at their limit every step, swayed the column's top at 8 cm/s for
// good (1 of 20 at rest at 20 s, at 600 sweeps). With shock propagation (contact_solver.h)
// seeds 1 to 8 but 4 rest by 2.75 s, most by 0.92 s. Seed 4 does not: its top seven cups
// lean as one on a rim edge (the top 1.3 m off the axis) and creep at 0.3 mm/s, jolted
// now and then by an event to 7 cm/s at the top.
TEST(BusyScenes, DroppedColumnOfTwentyCupsComesToRest) {
  for (unsigned long long seed : {1ull, 2ull, 3ull}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    World w(generated("cups", 20, seed));
    const Watched seen = run(w, 20.0);
    expectInvariants(w, seen);
    EXPECT_EQ(seen.stalledSteps, 0);
  }
}

// Columns of 8 cups, each turned up to 0.3 rad: they land tilted in each other's mouths,
// corners in corners and bottom edges across rims, then topple. Cups are not convex, so
// the polygons' measure judges them; where it read deeper than the contacts held (a rim
// corner inside another cup's corner, a bottom edge across a rim edge 100.8 um deep with
// no contact), an island's clock stood still and the column gained energy without bound.
// They came to rest only with shock propagation: before it, some jittered at the sweep
// limit for good. Seeds 1 to 4 now rest by 5.4 s.
TEST(BusyScenes, ColumnsOfTiltedCupsKeepTheEnergyBoundNeverStallAndComeToRest) {
  for (unsigned long long seed : {1ull, 2ull, 3ull}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    World w(generated("cups", 8, seed, 0.3));
    const Watched seen = run(w, 8.0);
    expectInvariants(w, seen);
    EXPECT_EQ(seen.stalledSteps, 0);
  }
}

// 20 cups (the generator's, each up to 5 cm off the column's axis) placed resting on each
// other's rims. Each rim is four convex pieces, reported as four areas sharing their
// corners; solved as four blocks, the copies traded load to the sweep limit every step,
// and the column gained 0.27 J (over 10 times its bound) and toppled, its cups 0.5 m
// off in 20 s. As one block of the rim's corners (contact_points.h) it stands.
TEST(BusyScenes, ColumnOfCupsPlacedAtRestStaysThere) {
  Scene scene = generated("cups", 20);
  int level = 0;
  for (BodySpec& b : scene.bodies)
    if (!b.isStatic) b.position.z() = 0.6 * level++, b.velocity.setZero();
  World w(scene);
  const Watched seen = run(w, 10.0);
  expectInvariants(w, seen);
  for (size_t i = 0; i < w.bodies().size(); ++i)
    EXPECT_LT((w.bodies()[i].position - scene.bodies[i].position).norm(), 1e-3) << scene.bodies[i].name;
}

// Columns of 20 frictionless cups. Seed 1 stands for 7 s, sways, and falls apart at 13 s;
// cups slide off each other's rims and wedge in each other's mouths while turning fast.
// There the gap-curvature targets once asked a wedged cup for 21 m/s of separation a
// step; its island could not move, so it spun faster and was asked for more, and the
// column gained 9,000 J (5e14 J with the rim's pieces merged) by 20 s. Seed 2 stalls at
// the event bound from 2.2 s, every event at the step's start: its cups kept each step's
// gravity in their speed without falling and gained 1,774 J in 4 s (196 kJ in 20 s).
// Not asserted: that the column never stalls (seed 2 still does).
TEST(BusyScenes, FrictionlessColumnOfCupsKeepsTheEnergyBound) {
  for (const auto& [seed, seconds] : {std::pair{1ull, 20.0}, std::pair{2ull, 4.0}, std::pair{3ull, 4.0}, std::pair{4ull, 4.0},
                                      std::pair{5ull, 4.0}}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Scene scene = generated("cups", 20, seed);
    scene.contact.friction = 0.0;
    for (BodySpec& b : scene.bodies) b.friction.reset();
    World w(scene);
    const Watched seen = run(w, seconds);
    EXPECT_TRUE(seen.finite);
    EXPECT_LE(seen.energyRise, energyBound(w));
    EXPECT_LE(seen.deepest, w.scene().contact.tolerance);
    EXPECT_EQ(seen.interpenetratingSteps, 0);
    // Seed 4 once stalled at the event bound nearly every step from 1.4 s: its touching
    // bodies stopped each time, and the column stood frozen with its top cups 0.3 m off
    // the axis (kept moving instead, they gained gravity: 3.6 m/s by 10 s). Since solves
    // after an event start from zero impulses, it stalled in 79 of 240 steps and toppled,
    // 1,200 J of its 1,575 J lost in impacts by 4 s; the energy bound guards it. It now
    // reaches the bound in 10 steps and stalls in none (nor do seeds 1 to 12, mu 0 or 0.5).
    // Seeds 2, 3 and 5 never reach the event bound in their first 4 s. With cups
    // speculating, their creases judged against walls 2 cm off that do not touch, each
    // did in 21 to 54 steps (seeds 1 to 8 all did).
    if (seed == 2 || seed == 3 || seed == 5) {
      EXPECT_EQ(seen.boundSteps, 0);
    }
  }
}

// 10 dominoes at tolerance 1e-5 m and dt 1/60 (found by the sweep): from 1.7 s the fallen
// row chatters in its 10 um band and its island reaches the event bound with eight events
// that each move on. The bodies in contact had been given the whole step's gravity; kept
// for the time the clock did not run, it gained 48 J (seed 1) and 71 J (seed 2) in 10 s.
// Not asserted: rest (the row still chatters at up to 4 cm/s).
TEST(BusyScenes, DominoesAtTheNarrowToleranceKeepTheEnergyBound) {
  for (unsigned long long seed : {1ull, 2ull}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Scene scene = generated("dominoes", 10, seed);
    scene.contact.tolerance = 1e-5;
    World w(scene);
    const Watched seen = run(w, 10.0);
    EXPECT_TRUE(seen.finite);
    EXPECT_LE(seen.energyRise, energyBound(w));
    EXPECT_LE(seen.deepest, w.scene().contact.tolerance);
    EXPECT_EQ(seen.interpenetratingSteps, 0);
  }
}

// 40 unit boxes resting on each other at dt 1/60 (the minute the issue asks for is
// measured by `polysim run`, see the README): each box within 0.1 mm of its column, each
// at its height within one tolerance per contact below it.
TEST(BusyScenes, StackOf40Stands) {
  World w(generated("stack", 40));
  const Watched seen = run(w, 5.0);
  expectInvariants(w, seen);
  const double eps = w.scene().contact.tolerance;
  for (int k = 0; k < 40; ++k) {
    const dynamics::RigidBody& b = w.bodies()[static_cast<size_t>(k) + 1];  // after the ground
    EXPECT_LT(b.position.head<2>().norm(), 1e-4) << "box" << k;
    EXPECT_NEAR(b.position.z(), 0.5 + k, (k + 1) * eps) << "box" << k;
  }
}

// The 20-box stack at rest, warm-started from each step's impulses, sorted bottom-up
// (the first sweep carries the weight to the ground in one pass): after its first second
// it takes 2.9 sweeps a step on average and never needs shock propagation. The sweeps'
// order is what this guards; with shock propagation settling what they leave, a stack
// sorted top-down stands too, at the cost of sweeps.
TEST(BusyScenes, RestingStackOf20TakesAFewSweepsAStep) {
  Scene scene = loadScene(std::string(POLYSIM_SCENES_DIR) + "/stack_20.json");
  scene.sleep.enabled = false;
  World w(scene);
  long sweeps = 0, shockSweeps = 0;
  const int settling = 60, steps = 300;
  for (int k = 0; k < steps; ++k) {
    const StepReport& r = w.step(scene.dt);
    if (k < settling) continue;
    sweeps += r.solverIterations;
    shockSweeps += r.shockSweeps;
  }
  EXPECT_LT(static_cast<double>(sweeps) / (steps - settling), 10.0);
  EXPECT_EQ(shockSweeps, 0);
}

// The pyramid of base 40 (820 boxes, centres 1.05 m apart): a wall 40 boxes high and one
// deep, each box on two below. For its first 3 s (10 s is the benchmark's and the
// README's run) every box stays within 1 cm of its start, the bound for 10 s.
// With every sweep bottom-up, the solver's 600 sweeps a step left the wall leaning out of
// its plane: its top moved 5 cm in 3 s, 4.8 cm by 10 s.
TEST(BusyScenes, PyramidOfBase40StandsWithinACentimetre) {
  World w(generated("pyramid", 40));
  std::vector<Eigen::Vector3d> start;
  for (const dynamics::RigidBody& b : w.bodies()) start.push_back(b.position);
  const Watched seen = run(w, 3.0, 60);
  EXPECT_TRUE(seen.finite);
  EXPECT_LE(seen.energyRise, energyBound(w));
  EXPECT_LE(seen.deepest, w.scene().contact.tolerance);
  EXPECT_EQ(seen.interpenetratingSteps, 0);
  double farthest = 0.0;
  for (size_t i = 0; i < start.size(); ++i) farthest = std::max(farthest, (w.bodies()[i].position - start[i]).norm());
  EXPECT_LT(farthest, 0.01);
  ::testing::Test::RecordProperty("farthest_m", std::to_string(farthest));
}

// The 10-box stack at tolerance 1e-5 m and dt 1/60 stands at the cost of 1e-4 m. Its
// faces used to turn beyond the narrower band and rock from edge to edge, every step at
// the event bound. Cost is counted as work (solver sweeps, events), not timed.
TEST(BusyScenes, TenStackAtTheNarrowToleranceStandsAtTheCostOfTheDefault) {
  struct Work {
    long sweeps = 0, events = 0, limitSteps = 0;
    double drift = 0.0;
  };
  auto runAt = [](double tolerance) {
    Scene scene = loadScene(std::string(POLYSIM_SCENES_DIR) + "/stack_10.json");
    scene.contact.tolerance = tolerance;
    scene.sleep.enabled = false;  // the solver's cost is compared, every step of it
    World w(scene);
    Work work;
    for (int k = 0; k < 600; ++k) {  // 10 s
      const StepReport& r = w.step(1.0 / 60);
      work.sweeps += r.solverIterations;
      work.events += static_cast<long>(r.events.size());
      work.limitSteps += r.eventLimitHit;
      EXPECT_LE(r.penetration, tolerance);
    }
    for (size_t i = 1; i < w.bodies().size(); ++i)
      work.drift = std::max(work.drift, (w.bodies()[i].position.head<2>() - scene.bodies[i].position.head<2>()).norm());
    return work;
  };
  const Work wide = runAt(1e-4), narrow = runAt(1e-5);
  EXPECT_EQ(narrow.limitSteps, 0);
  EXPECT_LT(narrow.drift, 1e-6);  // m in 10 s; it was 5.7 mm
  EXPECT_LE(narrow.sweeps, 1.5 * wide.sweeps + 600);
  EXPECT_LE(narrow.events, wide.events + 10);
}

// 10 dominoes (0.2 x 1 x 2 m, 0.9 to 1.1 m apart, the first tipped): each falls onto the
// next, in order, and the row ends at rest. The edge of one slides down the face of the
// next while that face turns towards it, so their gap closes quadratically within a step
// (the solver's curvature target), and where they come to lie on each other a corner's
// pieces disagree about its depth (the reduction's gap along the normal). Also without
// speculative contacts: every touch is then backed up to, the path that bodies flying
// free and bodies that are not convex still take.
TEST(BusyScenes, DominoesFallInOrderAndComeToRest) {
  for (const auto& [seed, reach] : {std::pair{1ull, kSpeculativeReach}, std::pair{2ull, kSpeculativeReach},
                                    std::pair{1ull, 0.0}, std::pair{2ull, 0.0}}) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", speculative reach " + std::to_string(reach));
    Scene scene = generated("dominoes", 10, seed);
    scene.contact.speculativeReach = reach;
    World w(scene);
    const double initial = w.energy();
    Watched seen;
    std::vector<double> firstTouch(9, -1.0);  // s: domino i meets domino i + 1
    for (int k = 0; k < 600; ++k) {
      const StepReport& r = w.step(w.scene().dt);
      seen.energyRise = std::max(seen.energyRise, w.energy() - initial);
      seen.deepest = std::max(seen.deepest, r.penetration);
      for (const dynamics::RigidBody& b : w.bodies()) seen.finite = seen.finite && b.position.allFinite();
      for (const collision::PairResult& p : w.contacts())
        if (p.b == p.a + 1 && p.a >= 1 && firstTouch[p.a - 1] < 0) firstTouch[p.a - 1] = r.time;  // bodies 1..10
    }
    expectInvariants(w, seen);
    for (size_t i = 0; i < firstTouch.size(); ++i) {
      EXPECT_GT(firstTouch[i], 0.0) << "domino" << i << " never reached the next";
      if (i > 0) {
        EXPECT_GT(firstTouch[i], firstTouch[i - 1]) << "domino" << i;
      }
    }
    for (size_t i = 1; i < w.bodies().size(); ++i) EXPECT_LT(w.bodies()[i].position.z(), 0.9) << "domino" << i - 1;
  }
}

// The same invariants on a pile small enough for the sanitizer builds: 8 tilted boxes.
TEST(BusyScenes, SmallTiltedPileUnderEveryBuild) {
  World w(generated("pile", 8, 3));
  const Watched seen = run(w, 4.0);
  expectInvariants(w, seen);
}

}  // namespace
}  // namespace polysim::sim
