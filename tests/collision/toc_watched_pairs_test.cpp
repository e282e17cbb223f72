// collisionDetect() watches, in its verdict-only tests, only the pairs that can
// interpenetrate in the interval (toc_search.h): a settled stack's resting pairs cannot
// while a body lands on top, so an event costs the landing, not the stack. Held here:
// such a pair really never interpenetrates, a pair the motion can push in is watched,
// and the contacts returned are still those of every pair.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "collision/shapes.h"
#include "collision/toc_search.h"
#include "collision/tolerances.h"
#include "tests/collision/toc_world.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using test::pose;
using test::TocWorld;
using V3 = Eigen::Vector3d;

constexpr double kEps = kDefaultContactTolerance;
const MeshData kCube = makeBox(V3(1, 1, 1));
const MeshData kSlab = makeBox(V3(10, 10, 1));
const Eigen::Isometry3d kSlabPose = pose(V3(0, 0, -0.5));  // top at z = 0

// Cube k of a stack on the slab, each sunk a quarter of the band into the one below (as
// the solver leaves resting pairs), drifting sideways by `drift` (m per interval): a
// settled body that still has a path.
int addStackedCube(TocWorld& w, int k, double drift, const V3& extra = V3::Zero()) {
  const double z = 0.5 + k * (1.0 - 0.25 * kEps) - 0.25 * kEps;
  return w.addMoving(kCube, pose(V3(0, 0, z)), V3(drift, 0, 0) + extra);
}

class WatchedPairs : public ::testing::TestWithParam<TocMethod> {};

// Five cubes settled on the slab; a sixth falls onto them from 0.5 m above at 1 m per
// interval: the contact is at t = 0.5. Only the falling pair is watched (its motion
// reaches the fourth cube as well, far too short to go in); the contacts returned are
// those of all six pairs in contact.
TEST_P(WatchedPairs, ASettledStackWaitsOnlyOnTheBodyLandingOnIt) {
  TocWorld w;
  w.addStatic(kSlab, kSlabPose);
  for (int k = 0; k < 5; ++k) addStackedCube(w, k, 1e-9);
  const double top = 5 * (1.0 - 0.25 * kEps) - 0.25 * kEps;
  w.addMoving(kCube, pose(V3(0, 0, top + 0.5 + 0.5)), V3(0, 0, -1.0));
  const TocResult r = w.detect(GetParam());
  EXPECT_EQ(r.status, Status::Contact);
  EXPECT_NEAR(r.time, 0.5, kEps / 1.0);  // within the band over the approach speed
  EXPECT_EQ(r.pairsMeeting, 7);
  EXPECT_EQ(r.pairsWatched, 1);
  ASSERT_EQ(r.pairs.size(), 6u);
  for (const PairResult& p : r.pairs) {
    EXPECT_EQ(p.status, Status::Contact) << p.a << "-" << p.b;
    EXPECT_FALSE(p.contacts.empty()) << p.a << "-" << p.b;
  }
}

// The same stack with its third cube pressing down at 20 tolerances per interval: it
// goes a tolerance deep into the second at t = 0.75 / 20, long before the landing, and
// the search must stop before that. Its pair is watched, and so is the one above it
// (motion bounds have no direction).
TEST_P(WatchedPairs, ARestingPairTheMotionCanPushInIsWatched) {
  TocWorld w;
  w.addStatic(kSlab, kSlabPose);
  for (int k = 0; k < 5; ++k) addStackedCube(w, k, 1e-9, k == 2 ? V3(0, 0, -20 * kEps) : V3::Zero());
  const double top = 5 * (1.0 - 0.25 * kEps) - 0.25 * kEps;
  w.addMoving(kCube, pose(V3(0, 0, top + 0.5 + 0.5)), V3(0, 0, -1.0));
  const TocResult r = w.detect(GetParam());
  EXPECT_EQ(r.status, Status::Contact);
  EXPECT_EQ(r.pairsWatched, 3);
  EXPECT_LE(r.time, 0.75 / 20);
  EXPECT_NE(test4Intersection(w.db).status, Status::Interpenetrating);
}

// Random convex bodies (boxes of random sizes, hexagonal prisms) resting on the slab at
// random tilts, their lowest corner anywhere from 0.95 tolerances deep to 3 apart, on
// random motions (mostly down) from a hundredth of a tolerance to ten. A pair the search leaves
// unwatched is tested at 65 times over the interval: it never interpenetrates. Cups (not
// convex) are always watched.
TEST(WatchedPairsRandom, APairLeftUnwatchedNeverInterpenetratesInTheInterval) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  int unwatched = 0, watchedAndCrossing = 0;
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    TocWorld w;
    w.addStatic(kSlab, kSlabPose);
    const int shape = trial % 5;
    const auto mesh = [&]() -> MeshData {
      if (shape == 4) return test::makeCup(0.5, 0.6, 0.08, 0.1);
      if (shape == 3) {
        const double across = 0.3 + 0.4 * unit(rng), height = 0.2 + 0.8 * unit(rng);
        return test::makeHexPrism(across, height);
      }
      return makeBox(V3::Constant(0.2) + test::drawnVector([&] { return unit(rng); }));
    }();
    const double angle = 0.6 * unit(rng);
    const Eigen::Matrix3d R = test::rot(angle, test::drawnVector([&] { return u(rng); }));
    double lowest = 0.0;
    for (const V3& v : mesh.vertices) lowest = std::min(lowest, (R * v).z());
    const double gap = -0.95 * kEps + 3.95 * kEps * unit(rng);
    const double motion = kEps * std::pow(10.0, -2.0 + 3.0 * unit(rng));  // 0.01 to 10 eps
    // Split the motion between a translation and a turn at random; the bound holds both.
    const double vx = u(rng), vy = u(rng), vz = -unit(rng);
    const V3 v = V3(vx, vy, vz).normalized() * motion * unit(rng);
    const V3 spin = test::drawnVector([&] { return u(rng); }).normalized() * (motion - v.norm()) / 1.5;  // farthest vertex < 1.5 m
    const int body = w.addMoving(mesh, pose(V3(0, 0, gap - lowest), R), v, spin);
    ASSERT_LE(w.db.objects[body].motionBound, 1.01 * motion);
    w.db.setTime(1.0);
    const toc::PairIds meeting = toc::pairsThatCanMeet(w.db);
    ASSERT_EQ(meeting.size(), 1u);
    IntersectionWorkspace ws;
    const bool watched = !toc::pairsThatCanInterpenetrate(w.db, ws, meeting).empty();
    if (shape == 4) {
      EXPECT_TRUE(watched) << "a pair that is not convex is always watched";
    }
    bool crosses = false;
    for (int k = 0; k <= 64; ++k) {
      w.db.setTime(k / 64.0);
      crosses = crosses || test4Intersection(w.db).status == Status::Interpenetrating;
    }
    if (!watched) {
      EXPECT_FALSE(crosses) << "unwatched, yet it interpenetrates";
    }
    unwatched += !watched;
    watchedAndCrossing += watched && crosses;
  }
  // Both sides of the rule are exercised.
  EXPECT_GT(unwatched, 200);
  EXPECT_GT(watchedAndCrossing, 20);
}

INSTANTIATE_TEST_SUITE_P(BothMethods, WatchedPairs, ::testing::Values(TocMethod::Bisection, TocMethod::RegulaFalsi),
                         [](const ::testing::TestParamInfo<TocMethod>& info) {
                           return info.param == TocMethod::Bisection ? std::string("Bisection") : std::string("RegulaFalsi");
                         });

}  // namespace
}  // namespace polysim::collision
