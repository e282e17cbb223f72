// The separating-axis measure of convex pairs (convex_separation.h) against analytic
// gaps and depths, and against the intersection test's verdicts on random poses.

#include "collision/convex_separation.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "collision/intersection.h"
#include "collision/shapes.h"
#include "collision/tolerances.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using test::pose;
using V3 = Eigen::Vector3d;

ObjectDatabase pairAt(const MeshData& a, const Eigen::Isometry3d& X_A, const MeshData& b, const Eigen::Isometry3d& X_B) {
  ObjectDatabase db;
  db.add("A", std::make_shared<PolygonMesh>(a), X_A, false);
  db.add("B", std::make_shared<PolygonMesh>(b), X_B, false);
  return db;
}

Eigen::Matrix3d turn(double angle, const V3& axis) { return Eigen::AngleAxisd(angle, axis).toRotationMatrix(); }

TEST(ConvexSeparation, DirectionsOfBoxesAndPrismsListedOnceCurvedShapesNotAtAll) {
  const PolygonMesh box(makeBox(V3(1, 2, 3))), prism(test::makeHexPrism(1.0, 0.5));
  EXPECT_EQ(box.faceDirections().size(), 3u);
  EXPECT_EQ(box.edgeDirections().size(), 3u);
  EXPECT_EQ(prism.faceDirections().size(), 4u);  // the caps' axis and three pairs of sides
  EXPECT_EQ(prism.edgeDirections().size(), 4u);  // the axis and three hexagon sides
  EXPECT_TRUE(PolygonMesh(makeIcosphere(1.0, 3)).faceDirections().empty());  // 640 directions
  EXPECT_TRUE(PolygonMesh(test::makeStaple()).faceDirections().empty());     // not convex
}

// Analytic cases under every world frame: face on face apart and overlapping, an edge
// over a face (box turned 45 degrees about x) and two crossing edges (one turned about x,
// the other about y), where the gap is between the edges along z.
TEST(ConvexSeparation, GapsAndDepthsOfBoxesMatchTheGeometry) {
  const MeshData cube = makeBox(V3(1, 1, 1));
  const double r = std::sqrt(0.5);  // half diagonal of a unit square
  struct Case {
    const char* name;
    Eigen::Isometry3d X_A, X_B;
    double expected;
  };
  const Case cases[] = {
      {"face_gap", pose(V3::Zero()), pose(V3(0.3, 0.2, 1.25)), 0.25},
      {"face_overlap", pose(V3::Zero()), pose(V3(0.3, 0.2, 0.9)), -0.1},
      {"edge_over_face", pose(V3::Zero()), pose(V3(0.1, 0, 0.5 + r + 0.03), turn(M_PI / 4, V3::UnitX())), 0.03},
      {"crossing_edges", pose(V3::Zero(), turn(M_PI / 4, V3::UnitX())),
       pose(V3(0, 0, 2 * r + 0.02), turn(M_PI / 4, V3::UnitY())), 0.02},
      {"crossing_edges_overlap", pose(V3::Zero(), turn(M_PI / 4, V3::UnitX())),
       pose(V3(0, 0, 2 * r - 0.01), turn(M_PI / 4, V3::UnitY())), -0.01},
  };
  for (const Case& c : cases)
    for (const test::NamedFrame& frame : test::worldFrames()) {
      const ObjectDatabase db = pairAt(cube, frame.X * c.X_A, cube, frame.X * c.X_B);
      const std::optional<double> s = convexSeparation(db.objects[0], db.objects[1]);
      ASSERT_TRUE(s.has_value());
      EXPECT_NEAR(*s, c.expected, 1e-12) << c.name << " in the " << frame.name << " frame";
      EXPECT_NEAR(*convexSeparation(db.objects[1], db.objects[0]), c.expected, 1e-12) << c.name << " swapped";
    }
}

TEST(ConvexSeparation, NoMeasureForNonConvexOrCurvedMeshes) {
  const ObjectDatabase db = pairAt(makeBox(V3(1, 1, 1)), pose(V3::Zero()), test::makeL(), pose(V3(3, 0, 0)));
  EXPECT_FALSE(convexSeparation(db.objects[0], db.objects[1]).has_value());
  const ObjectDatabase spheres = pairAt(makeIcosphere(1, 3), pose(V3::Zero()), makeBox(V3(1, 1, 1)), pose(V3(3, 0, 0)));
  EXPECT_FALSE(convexSeparation(spheres.objects[0], spheres.objects[1]).has_value());
}

// A wedge: a right triangle 1 x 0.6 extruded 0.8 deep. Convex, not symmetric about any
// point (its extents are found by scanning all its vertices).
MeshData makeWedge() {
  using V = Eigen::Vector2d;
  return test::extrudeProfile({{V(0, 0), V(1, 0), V(0, 0.6)}}, {V(0, 0), V(1, 0), V(0, 0.6)}, 0.8);
}

TEST(ConvexSeparation, BoxesAndEvenPrismsAreScannedByHalfWedgesWhole) {
  const PolygonMesh box(makeBox(V3(1, 2, 3))), prism(test::makeHexPrism(1.0, 0.5)), wedge(makeWedge());
  EXPECT_EQ(box.mirroredHalf().size(), 4u);
  EXPECT_TRUE(box.centre().isZero(1e-15));
  EXPECT_EQ(prism.mirroredHalf().size(), 6u);
  EXPECT_TRUE(wedge.mirroredHalf().empty());
}

// On random poses of a box and another convex shape the measure agrees with the polygon
// tests: more than eps apart means separate, separate means apart (positive), and more
// than eps overlapping along every axis means interpenetrating (collisionDetect's scan
// relies on the last).
void expectAgreementOnRandomPoses(const MeshData& other, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> distance(0.3, 1.6);
  int apart = 0, overlapping = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const auto rotation = [&] { return test::drawnQuaternion([&] { return g(rng); }).normalized().toRotationMatrix(); };
    const Eigen::Matrix3d first = rotation();
    const double apartBy = distance(rng);
    const V3 direction = test::drawnVector([&] { return g(rng); }).normalized();
    const ObjectDatabase db = pairAt(makeBox(V3(1, 0.6, 0.8)), pose(V3::Zero(), first), other, pose(apartBy * direction, rotation()));
    const double s = *convexSeparation(db.objects[0], db.objects[1]);
    const Status status = test4Intersection(db).status;
    if (s > db.tolerance) {
      EXPECT_EQ(status, Status::Separate) << "trial " << trial << ", separation " << s;
    }
    if (status == Status::Separate) {
      EXPECT_GT(s, 0.0) << "trial " << trial;
    }
    if (s < -db.tolerance) {
      EXPECT_EQ(status, Status::Interpenetrating) << "trial " << trial << ", separation " << s;
    }
    apart += s > db.tolerance;
    overlapping += s < -db.tolerance;
  }
  EXPECT_GT(apart, 100);  // both sides are exercised
  EXPECT_GT(overlapping, 100);
}

TEST(ConvexSeparation, AgreesWithTheIntersectionTestOnRandomPosesOfABoxAndAPrism) {
  expectAgreementOnRandomPoses(test::makeHexPrism(0.5, 0.7), 5);
}

TEST(ConvexSeparation, AgreesWithTheIntersectionTestOnRandomPosesOfABoxAndAWedge) {
  expectAgreementOnRandomPoses(makeWedge(), 6);
}

}  // namespace
}  // namespace polysim::collision
