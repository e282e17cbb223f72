// A face on a flat patch of triangles (area_on_patch.h), through test4Intersection():
// where the pieces cover the face, nearly cover it, or lie on two planes of a step.

#include <gtest/gtest.h>

#include <memory>

#include "collision/intersection.h"
#include "collision/shapes.h"
#include "collision/tolerances.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using test::pose;
using V3 = Eigen::Vector3d;

constexpr double kEps = kDefaultContactTolerance;

double polygonArea(const Contact& c) {
  V3 twice = V3::Zero();
  for (size_t i = 0; i < c.points.size(); ++i) twice += c.points[i].cross(c.points[(i + 1) % c.points.size()]);
  return 0.5 * twice.dot(c.normal);
}

// The contacts of a unit box at `X_box` on a static `floor`.
PairResult boxOn(const MeshData& floor, const Eigen::Isometry3d& X_box) {
  ObjectDatabase db;
  db.tolerance = kEps;
  db.add("box", std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1))), X_box, false);
  db.add("floor", std::make_shared<PolygonMesh>(floor), pose(V3::Zero()), true);
  const IntersectionResult r = test4Intersection(db);
  return r.pairs.empty() ? PairResult{} : r.pairs[0];
}

// Overhanging the floor's edge by two tolerances leaves the pieces short of the face by a
// strip far thinner than the face: the contact is the overlap, not the face.
TEST(AreaOnPatch, FaceShortOfCoverByAThinStripGivesTheOverlap) {
  const double overhang = 2 * kEps;
  const PairResult pair = boxOn(makeTriangulatedFloor(6, 6, 12), pose(V3(2.5 + overhang, 0, 0.5)));
  ASSERT_EQ(pair.status, Status::Contact);
  // Nothing else: the box's edge beyond the floor's corner is two tolerances away from it
  // (an edge clipped against a triangle grown by eps used to report a point there).
  ASSERT_EQ(pair.contacts.size(), 1u);
  const Contact& area = pair.contacts[0];
  EXPECT_EQ(area.type, ContactType::Area);
  EXPECT_NEAR(polygonArea(area), 1.0 - overhang, 1e-12);
  for (const V3& x : area.points) EXPECT_LE(x.x(), 3.0 + 1e-12);
}

// Two halves of a floor, the right one raised by 0.4 tolerance: far more than a face may
// be off its plane (kPlanarityTolerance), so the right half is no part of the left's patch,
// but within the band, so the box between them rests on both in one area. Its bottom is
// 0.2 tolerance above the left half (a quarter of the face) and 0.2 below the right: each
// corner keeps its own gap, and the area's separation is the deeper, -0.2 tolerance.
TEST(AreaOnPatch, StepWithinTheBandIsOneArea) {
  const double step = 0.4 * kEps;
  MeshData floor;
  floor.vertices = {V3(-2, -2, 0), V3(0, -2, 0), V3(0, 2, 0), V3(-2, 2, 0),
                    V3(0, -2, step), V3(2, -2, step), V3(2, 2, step), V3(0, 2, step)};
  floor.faces = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const PairResult pair = boxOn(floor, pose(V3(0.25, 0.1, 0.5 + step / 2)));
  ASSERT_EQ(pair.status, Status::Contact);
  ASSERT_EQ(pair.contacts.size(), 1u);
  const Contact& area = pair.contacts[0];
  EXPECT_EQ(area.type, ContactType::Area);
  EXPECT_NEAR(polygonArea(area), 1.0, 1e-9);
  EXPECT_NEAR(area.separation, -0.2 * kEps, 1e-12);
  ASSERT_EQ(area.gaps.size(), area.points.size());
  for (size_t i = 0; i < area.points.size(); ++i) {
    const V3& x = area.points[i];
    EXPECT_NEAR(area.gaps[i], x.x() < 0 ? 0.2 * kEps : -0.2 * kEps, 1e-12) << x.transpose();
    EXPECT_GE(x.z(), -kEps);
    EXPECT_LE(x.z(), step + kEps);
  }
}

}  // namespace
}  // namespace polysim::collision
