// collisionDetect() without the gather at an event (TocOptions::gatherAtEvent off, as the
// step loop runs it): the time, verdict and crossing pairs are the gathering search's;
// the contacts given are the crossing pairs' only; and the watched pairs that may have
// come within the band by the event's time are named (TocResult::nearing), so that a
// caller keeping older contacts knows which to test again.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "collision/convex_separation.h"
#include "collision/intersection.h"
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
const MeshData kSlab = makeBox(V3(40, 40, 1));
const Eigen::Isometry3d kSlabPose = pose(V3(0, 0, -0.5));  // top at z = 0

TocOptions local() {
  TocOptions o;
  o.gatherAtEvent = false;
  return o;
}

bool has(const std::vector<std::pair<int, int>>& pairs, int a, int b) {
  return std::find(pairs.begin(), pairs.end(), std::pair{std::min(a, b), std::max(a, b)}) != pairs.end();
}

// Cube `fast` lands on the slab at t = 0.5. Cube `slow`, elsewhere, sinks 10 bands an
// interval from 5.5 bands up: at t = 0.5 it is half a band above the slab, within the
// band and far from interpenetrating (that comes at about t = 0.64). Cube `high` is far
// above anything. Only the landing is given with contacts; `slow` is named as nearing.
TEST(EventLocalSearch, NamesThePairsThatCameWithinTheBandByTheEvent) {
  const auto build = [](TocWorld& w) {
    w.addStatic(kSlab, kSlabPose);
    const int fast = w.addMoving(kCube, pose(V3(0, 0, 1.0)), V3(0, 0, -1.0));
    const int slow = w.addMoving(kCube, pose(V3(5, 0, 0.5 + 5.5 * kEps)), V3(0, 0, -10 * kEps));
    const int high = w.addMoving(kCube, pose(V3(-5, 0, 3.0)), V3(0, 0, -0.1));
    return std::tuple{fast, slow, high};
  };
  TocWorld w;
  const auto [fast, slow, high] = build(w);
  const TocResult r = w.detect(local());
  EXPECT_NEAR(r.time, 0.5, kEps);
  ASSERT_EQ(r.crossing.size(), 1u);
  EXPECT_TRUE(has(r.crossing, 0, fast));
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_FALSE(r.pairs[0].contacts.empty());
  EXPECT_EQ(r.nearing, (std::vector<std::pair<int, int>>{{0, slow}}));
  EXPECT_FALSE(has(r.nearing, 0, high));

  TocWorld gathered;
  build(gathered);
  const TocResult g = gathered.detect(TocOptions{});
  EXPECT_EQ(g.time, r.time);
  EXPECT_EQ(g.crossing, r.crossing);
  EXPECT_EQ(g.pairs.size(), 2u) << "the gathering search finds the slow cube in contact too";
  EXPECT_TRUE(g.nearing.empty());
}

// Seeded rows of tilted cubes falling onto the slab at random speeds, spinning about the
// vertical, timed to land within a few bands' travel of each other: the search without
// the gather finds the gathering one's time, status and crossing pairs; gives contacts
// only for the crossing pairs; leaves nothing interpenetrating at its time (a full test
// of every pair); and names as nearing every watched pair other than the crossing ones
// that the gather finds in contact there but that was apart by more than the band at the
// interval's start.
TEST(EventLocalSearch, RandomLandingsFindTheGatheringSearchsEventAndNameItsNewTouches) {
  int events = 0, named = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    const auto build = [&](TocWorld& w, std::mt19937 r) {
      std::uniform_real_distribution<double> v(-1.0, 1.0);
      w.addStatic(kSlab, kSlabPose);
      for (int k = 0; k < 12; ++k) {
        const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3 * v(r), V3(v(r), v(r), 0.3).normalized()).toRotationMatrix();
        double lowest = 0.0;  // the lowest corner's height below the centre
        for (int c = 0; c < 8; ++c)
          lowest = std::min(lowest, (R * V3(c & 1 ? 0.5 : -0.5, c & 2 ? 0.5 : -0.5, c & 4 ? 0.5 : -0.5)).z());
        const double speed = 0.6 + 0.5 * (v(r) + 1.0);
        const double landsAt = 0.5 + (v(r) + 1.0) * kEps / speed;  // within two bands' travel of t = 0.5
        const V3 at(1.8 * (k % 4), 1.8 * (k / 4), -lowest + speed * landsAt);
        w.addMoving(kCube, pose(at, R), V3(0, 0, -speed), V3(0, 0, 0.5 * v(r)));
      }
    };
    TocWorld w, gathered;
    build(w, rng);
    build(gathered, rng);
    toc::PairIds watched;
    {
      IntersectionWorkspace ws;
      const toc::Search s{w.db, ws};
      watched = s.watched;
      for (const auto& [a, b] : s.meeting) {  // apart by more than the band at the start
        w.db.setTime(0.0);
        const std::optional<double> apart = convexSeparation(w.db.objects[a], w.db.objects[b]);
        if (!apart || *apart <= kEps) watched.erase(std::remove(watched.begin(), watched.end(), std::pair{a, b}), watched.end());
      }
    }
    const TocResult r = w.detect(local());
    const TocResult g = gathered.detect(TocOptions{});
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_EQ(r.time, g.time);
    EXPECT_EQ(r.status, g.status);
    EXPECT_EQ(r.crossing, g.crossing);
    if (r.crossing.empty()) continue;
    ++events;
    for (const PairResult& p : r.pairs) EXPECT_TRUE(has(r.crossing, p.a, p.b)) << p.a << "-" << p.b;
    IntersectionOptions verdict;
    verdict.contacts = false;
    EXPECT_NE(test4Intersection(w.db, verdict).status, Status::Interpenetrating);
    for (const auto& [a, b] : r.nearing) EXPECT_FALSE(has(r.crossing, a, b));
    for (const PairResult& p : g.pairs) {
      const auto [a, b] = std::minmax(p.a, p.b);
      if (has(r.crossing, a, b) || !has(watched, a, b)) continue;
      EXPECT_TRUE(has(r.nearing, a, b)) << a << "-" << b << " came within the band unnamed";
      ++named;
    }
  }
  EXPECT_GT(events, 30);
  EXPECT_GT(named, 10) << "new touches at events are common in these piles";
}

}  // namespace
}  // namespace polysim::collision
