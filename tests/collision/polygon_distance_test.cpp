// polygonDistance() (polygon_distance.h) against the geometry of squares placed face to
// face, edge across edge and corner over face, and its early answer for a caller that
// already knows a smaller distance.

#include "collision/polygon_distance.h"

#include <gtest/gtest.h>

#include <array>

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;

// A square of side 2 h in the plane through `centre` spanned by u and v (normal u x v).
struct Square {
  std::array<V3, 4> corners;
  PolygonView view;
  Square(const V3& centre, const V3& u, const V3& v, double h) {
    corners = {centre - h * u - h * v, centre + h * u - h * v, centre + h * u + h * v, centre - h * u + h * v};
    view.vertices = corners.data();
    view.size = 4;
    view.plane.normal = u.cross(v).normalized();
    view.plane.offset = view.plane.normal.dot(centre);
  }
  Square(const Square&) = delete;  // the view points into this object
};

TEST(PolygonDistance, MatchesTheGeometryOfSquares) {
  PolygonScratch scratch;
  const V3 x = V3::UnitX(), y = V3::UnitY(), z = V3::UnitZ();
  const Square floor(V3::Zero(), x, y, 1.0);
  const Square above(V3(0.5, 0.2, 0.3), y, x, 0.5);                  // face to face, 0.3 up
  const Square standing(V3(1.4, 0, 0.5), y, z, 0.4);                 // edge 0.4 past the floor's edge, 0.1 up
  const Square crossing(V3(0, 0, -0.1), z, V3(1, 1, 0).normalized(), 0.2);  // through the floor
  EXPECT_NEAR(polygonDistance(floor.view, above.view, scratch), 0.3, 1e-12);
  EXPECT_NEAR(polygonDistance(floor.view, standing.view, scratch), std::hypot(0.4, 0.1), 1e-12);
  EXPECT_EQ(polygonDistance(floor.view, crossing.view, scratch), 0.0);
}

TEST(PolygonDistance, ReturnsAPlaneGapAtOnceWhenItCannotBeatTheLeast) {
  PolygonScratch scratch;
  const V3 x = V3::UnitX(), y = V3::UnitY();
  const Square floor(V3::Zero(), x, y, 1.0);
  const Square above(V3(3.0, 0, 0.3), y, x, 0.5);  // 0.3 above the floor's plane, 2 m to the side
  const double exact = polygonDistance(floor.view, above.view, scratch);
  EXPECT_NEAR(exact, std::hypot(1.5, 0.3), 1e-12);
  // The plane gap (0.3) cannot beat a least of 0.2: it comes back, a bound >= 0.2.
  EXPECT_NEAR(polygonDistance(floor.view, above.view, scratch, 0.2), 0.3, 1e-12);
  // A least above the plane gap needs the exact distance.
  EXPECT_NEAR(polygonDistance(floor.view, above.view, scratch, 1.0), exact, 1e-12);
}

}  // namespace
}  // namespace polysim::collision
