#include "collision/clip.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

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

// The hull of a point set without collinear corners is the counter-clockwise polygon of
// input points, turning left at every corner, with every input point on or inside it.
void expectIsHullOf(const Polygon2& hull, const std::vector<V2>& points) {
  ASSERT_GE(hull.size(), 3u);
  for (size_t i = 0; i < hull.size(); ++i) {
    const V2 &a = hull[i], &b = hull[(i + 1) % hull.size()], &c = hull[(i + 2) % hull.size()];
    EXPECT_GT(cross2(b - a, c - b), 0.0) << "corner " << (i + 1) % hull.size();
    EXPECT_NE(std::find(points.begin(), points.end(), a), points.end()) << "corner " << i << " is not an input";
  }
  for (const V2& p : points) EXPECT_LE(distanceToConvex(hull, p), 1e-12) << p.transpose();
}

TEST(Clip, HullOfALatticeIsItsFourCorners) {
  // Ties in x and in y everywhere, as the corners of a triangulated floor's pieces.
  std::vector<V2> lattice;
  for (int i = 0; i <= 9; ++i)
    for (int j = 0; j <= 6; ++j) lattice.emplace_back(0.1 * i, 0.2 * j);
  const Polygon2 hull = convexHull(lattice);
  EXPECT_EQ(hull.size(), 4u);
  expectIsHullOf(hull, lattice);
  EXPECT_NEAR(signedArea(hull), 0.9 * 1.2, 1e-12);
}

TEST(Clip, HullOfRandomCloudsHoldsEveryPoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int cloud = 0; cloud < 200; ++cloud) {
    std::vector<V2> points;
    const int n = 3 + cloud % 60;
    const V2 centre = cloud % 3 == 0 ? V2(0.0, 0.0) : V2(5.0, -2.0);
    for (int i = 0; i < n; ++i) {
      const double x = coordinate(rng), y = coordinate(rng);  // in this order, whatever the compiler
      points.push_back(centre + V2(x, y));
    }
    if (cloud % 2) points.push_back(points.front());  // a duplicate
    expectIsHullOf(convexHull(points), points);
  }
}

TEST(Clip, DistanceToConvexIsZeroInsideAndEuclideanOutside) {
  EXPECT_EQ(distanceToConvex(square(1.0), V2(0.5, 0.5)), 0.0);
  EXPECT_NEAR(distanceToConvex(square(1.0), V2(4, 5)), 5.0, 1e-12);
}

// Square [-1, 1]^2. The line x + y = 3 passes its corner (1, 1) nearest at (1.5, 1.5),
// sqrt(0.5) away, with neither end near; a segment pointing away is nearest at its end.
TEST(Clip, NearestPointOfASegmentToAConvexPolygon) {
  const V2 nearCorner = nearestPointToConvex(square(1.0), V2(3, 0), V2(0, 3));
  EXPECT_NEAR((nearCorner - V2(1.5, 1.5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(distanceToConvex(square(1.0), nearCorner), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR((nearestPointToConvex(square(1.0), V2(5, 0.5), V2(2, 0.5)) - V2(2, 0.5)).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace polysim::collision
