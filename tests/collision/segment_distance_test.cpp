// closestPointsOnSegments(): the closest points of two segments, with their parameters,
// against points found by brute force along both segments.

#include "collision/segment_distance.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;

// Seeded random segments in a unit cube, half of them meeting nearly end to end: the
// distance matches a search over both segments (to its grid's resolution), the points
// are the segments' at the parameters given, and a parameter at an end is exactly 0 or 1,
// so that callers can tell an end from a point inside (crease_depth.cpp).
TEST(SegmentDistance, ParametersGiveThePointsAndEndsAreExact) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random = [&]() -> V3 { return test::drawnVector([&] { return unit(rng); }); };
  int atAnEnd = 0, inside = 0;
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const V3 p0 = random(), u = random();
    // Half the second segments start just past the first's end, turned at random.
    const V3 q0 = trial % 2 ? V3(p0 + 1.01 * u + 0.01 * random()) : random();
    const V3 v = random();
    const SegmentClosestPoints cp = closestPointsOnSegments(p0, u, q0, v);
    EXPECT_GE(cp.s, 0.0);
    EXPECT_LE(cp.s, 1.0);
    EXPECT_GE(cp.t, 0.0);
    EXPECT_LE(cp.t, 1.0);
    EXPECT_LT((cp.onFirst - (p0 + cp.s * u)).norm(), 1e-15);
    EXPECT_LT((cp.onSecond - (q0 + cp.t * v)).norm(), 1e-15);
    EXPECT_NEAR(cp.distance, (cp.onFirst - cp.onSecond).norm(), 1e-15);
    double best = std::numeric_limits<double>::infinity();
    constexpr int kSteps = 400;
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; j <= kSteps; ++j) best = std::min(best, (p0 + (i / double(kSteps)) * u - q0 - (j / double(kSteps)) * v).norm());
    EXPECT_LE(cp.distance, best + 1e-12);
    EXPECT_GE(cp.distance, best - (u.norm() + v.norm()) / kSteps);
    const bool end = cp.s == 0.0 || cp.s == 1.0 || cp.t == 0.0 || cp.t == 1.0;
    (end ? atAnEnd : inside) += 1;
  }
  EXPECT_GT(atAnEnd, 50);
  EXPECT_GT(inside, 10);
}

}  // namespace
}  // namespace polysim::collision
