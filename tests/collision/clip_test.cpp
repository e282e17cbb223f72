#include "collision/clip.h"

#include <gtest/gtest.h>

namespace polysim::collision {
namespace {

using V2 = Eigen::Vector2d;

Polygon2 square(double h, V2 c = V2::Zero()) { return {c + V2(-h, -h), c + V2(h, -h), c + V2(h, h), c + V2(-h, h)}; }

TEST(Clip, OverlapOfTwoSquaresIsTheirIntersection) {
  const Polygon2 overlap = clipConvex(square(1.0), square(1.0, V2(1.5, 0.5)));
  EXPECT_NEAR(signedArea(overlap), 0.5 * 1.5, 1e-12);
}

TEST(Clip, DisjointSquaresHaveNoOverlap) {
  EXPECT_TRUE(clipConvex(square(1.0), square(1.0, V2(3, 0))).empty());
}

TEST(Clip, SegmentIsCutAtTheGrownBoundary) {
  V2 a(-5, 0), b(5, 0);
  ASSERT_TRUE(clipSegment(square(1.0), 0.25, a, b));
  EXPECT_NEAR(a.x(), -1.25, 1e-12);
  EXPECT_NEAR(b.x(), 1.25, 1e-12);
  V2 c(-5, 2), d(5, 2);
  EXPECT_FALSE(clipSegment(square(1.0), 0.25, c, d));
}

TEST(Clip, SegmentEndsInsideAreKeptExactly) {
  // Callers compare a kept end with the vertex it came from (polygon_tests.cpp).
  const V2 inside(0.1 / 3, -0.7 / 3), outside(5.0 / 7, 3.1);
  V2 a = inside, b = outside;
  ASSERT_TRUE(clipSegment(square(1.0), 0.0, a, b));
  EXPECT_EQ(a, inside);
  EXPECT_NE(b, outside);
  V2 c = outside, d = inside;
  ASSERT_TRUE(clipSegment(square(1.0), 0.0, c, d));
  EXPECT_EQ(d, inside);
}

TEST(Clip, HullDropsInteriorAndCollinearPoints) {
  const Polygon2 hull = convexHull({V2(0, 0), V2(1, 0), V2(2, 0), V2(2, 2), V2(0, 2), V2(1, 1)});
  EXPECT_EQ(hull.size(), 4u);
  EXPECT_NEAR(signedArea(hull), 4.0, 1e-12);
}

TEST(Clip, DistanceToConvexIsZeroInsideAndEuclideanOutside) {
  EXPECT_EQ(distanceToConvex(square(1.0), V2(0.5, 0.5)), 0.0);
  EXPECT_NEAR(distanceToConvex(square(1.0), V2(4, 5)), 5.0, 1e-12);
}

}  // namespace
}  // namespace polysim::collision
