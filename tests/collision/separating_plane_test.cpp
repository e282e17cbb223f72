// The quick separation proof (separating_plane.h) and what it rests on: the mesh's
// convexity flag and the hill-climbing extreme vertex.

#include "collision/separating_plane.h"

#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <random>

#include "collision/broadphase.h"
#include "collision/shapes.h"
#include "collision/tolerances.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;

// One mesh made of two copies of `piece`, the second 3 m along x: closed and locally
// convex when the piece is, but not convex (two pieces).
MeshData twoOf(const MeshData& piece) {
  MeshData m = piece;
  const int shift = static_cast<int>(m.vertices.size());
  for (const V3& v : piece.vertices) m.vertices.push_back(v + V3(3, 0, 0));
  for (std::vector<int> f : piece.faces) {
    for (int& i : f) i += shift;
    m.faces.push_back(f);
  }
  return m;
}

// Two unit boxes side by side in one mesh.
MeshData twoBoxes() { return twoOf(makeBox(V3(1, 1, 1))); }

TEST(ConvexMesh, BoxesSpheresAndPrismsAreConvexCupsStaplesFloorsAndPairsAreNot) {
  EXPECT_TRUE(PolygonMesh(makeBox(V3(1, 2, 3))).convex());
  EXPECT_TRUE(PolygonMesh(makeIcosphere(1.0, 3)).convex());
  EXPECT_TRUE(PolygonMesh(test::makeHexPrism(1.0, 0.5)).convex());
  EXPECT_FALSE(PolygonMesh(test::makeStaple()).convex());
  EXPECT_FALSE(PolygonMesh(test::makeL()).convex());
  EXPECT_FALSE(PolygonMesh(test::makeCup(1.0, 1.0, 0.1, 0.1)).convex());
  EXPECT_FALSE(PolygonMesh(makeTriangulatedFloor(2, 2, 3)).convex());  // open
  EXPECT_FALSE(PolygonMesh(twoBoxes()).convex());                     // not connected
}

TEST(ConvexMesh, ExtremeVertexMatchesAScanOfEveryVertex) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  for (const MeshData& data : {makeIcosphere(1.0, 4), makeBox(V3(1, 2, 3)), test::makeHexPrism(1.0, 0.5)}) {
    const PolygonMesh mesh(data);
    for (int trial = 0; trial < 300; ++trial) {
      const V3 d = test::drawnVector([&] { return g(rng); });
      double best = -1e300;
      for (const V3& v : mesh.vertices()) best = std::max(best, d.dot(v));
      EXPECT_DOUBLE_EQ(d.dot(mesh.vertices()[mesh.extremeVertex(d)]), best) << "direction " << d.transpose();
    }
  }
}

ObjectDatabase pairAt(const MeshData& a, const MeshData& b, const Eigen::Isometry3d& X_A, const Eigen::Isometry3d& X_B) {
  ObjectDatabase db;
  db.add("A", std::make_shared<PolygonMesh>(a), X_A, false);
  db.add("B", std::make_shared<PolygonMesh>(b), X_B, false);
  return db;
}

// Unit boxes (convex) and staples (branch and bound over the grid) side by side along x,
// a gap apart, under every world frame: twice the tolerance is proven apart, half of it
// (a contact) and an overlap are not.
TEST(SeparatingPlane, GapAlongTheCentreLineDecidedAtTheTolerance) {
  const double eps = kDefaultContactTolerance;
  struct Shape {
    const char* name;
    MeshData mesh;
    double width;  // along x
  };
  for (const Shape& shape : {Shape{"box", makeBox(V3(1, 1, 1)), 1.0}, Shape{"staple", test::makeStaple(), 3.0}})
    for (const test::NamedFrame& frame : test::worldFrames())
      for (double gap : {2 * eps, 0.5 * eps, -0.01}) {
        const ObjectDatabase db = pairAt(shape.mesh, shape.mesh, frame.X * test::pose(V3::Zero()),
                                         frame.X * test::pose(V3(shape.width + gap, 0, 0)));
        EXPECT_EQ(separatedAlongCentreLine(db.objects[0], db.objects[1], eps), gap > eps)
            << shape.name << " in the " << frame.name << " frame, gap " << gap;
      }
}

TEST(SeparatingPlane, IcospheresATenthApartAreProvenApart) {
  const MeshData sphere = makeIcosphere(1.0, 5);
  const V3 axis = V3(1, 1, 1).normalized();
  for (double distance : {2.1, 1.9}) {
    const ObjectDatabase db = pairAt(sphere, sphere, test::pose(V3::Zero()), test::pose(distance * axis));
    EXPECT_EQ(separatedAlongCentreLine(db.objects[0], db.objects[1], kDefaultContactTolerance), distance > 2.0);
  }
}

// Whenever the plane test answers "apart", every vertex of B lies more than eps beyond
// every vertex of A along some direction, checked here along the centre line by a scan.
TEST(SeparatingPlane, NeverClaimsApartWhatAScanOfVerticesDenies) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> distance(2.0, 4.5);
  const MeshData staple = test::makeStaple(), cup = test::makeCup(1.0, 1.5, 0.2, 0.2);
  int apart = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const auto rotation = test::drawnQuaternion([&] { return g(rng); }).normalized().toRotationMatrix();
    const double apartBy = distance(rng);
    const V3 direction = test::drawnVector([&] { return g(rng); }).normalized();
    const ObjectDatabase db =
        pairAt(staple, trial % 2 ? cup : staple, test::pose(V3::Zero()), test::pose(apartBy * direction, rotation));
    const ObjNode &a = db.objects[0], &b = db.objects[1];
    if (!separatedAlongCentreLine(a, b, kDefaultContactTolerance)) continue;
    ++apart;
    const V3 d = (worldContainer(b).center() - worldContainer(a).center()).normalized();
    double top = -1e300, bottom = 1e300;
    for (const V3& v : a.mesh->vertices()) top = std::max(top, d.dot(a.X_WO * v));
    for (const V3& v : b.mesh->vertices()) bottom = std::min(bottom, d.dot(b.X_WO * v));
    EXPECT_GT(bottom - top, kDefaultContactTolerance) << "trial " << trial;
  }
  EXPECT_GT(apart, 40);   // the test has cases to check
  EXPECT_LT(apart, 380);  // and the plane does not settle every pose
}

// Two icospheres (radius 1, 1280 triangles each) side by side in one mesh: closed,
// locally convex, not convex, and with enough faces that its voxel grid is a real tree,
// so its extent is bounded by branch and bound over the grid (the staple and the cup
// above get no halvings and are scanned whole).
MeshData twoSpheres() { return twoOf(makeIcosphere(1.0, 3)); }

// The highest vertex level along d, by a scan of every vertex (object frame).
double scannedTop(const ObjNode& object, const V3& d) {
  double top = -1e300;
  for (const V3& v : object.mesh->vertices()) top = std::max(top, d.dot(v));
  return top;
}

TEST(SeparatingPlane, BranchAndBoundTopIsAVertexWithinTheSlackOfTheScannedTop) {
  ObjectDatabase db;
  db.add("spheres", std::make_shared<PolygonMesh>(twoSpheres()), test::pose(V3::Zero()), false);
  const ObjNode& spheres = db.objects[0];
  ASSERT_GE(spheres.grid->halvings(), 4) << "the mesh must get a voxel tree for this test to mean anything";
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 300; ++trial) {
    const V3 d = test::drawnVector([&] { return g(rng); }).normalized();
    const double top = scannedTop(spheres, d);
    for (double slack : {0.0, 0.01, 0.3}) {
      const double level = topLevelAlong(spheres, d, slack, -std::numeric_limits<double>::infinity());
      EXPECT_LE(level, top) << "not a vertex's level, d " << d.transpose();
      EXPECT_GE(level, top - slack) << "more than the slack " << slack << " below the top, d " << d.transpose();
    }
  }
}

// A box placed around the two-sphere mesh at random, from well apart to overlapping by
// a few centimetres, along the line from the mesh's container centre: whenever the plane
// test says "apart", a scan of both meshes' vertices along that line must agree. With
// the non-convex bound's slack dropped it said "apart" at 5 mm of overlap.
TEST(SeparatingPlane, NonConvexMeshWithAVoxelTreeIsNeverClaimedApartWhenItOverlaps) {
  auto spheres = std::make_shared<PolygonMesh>(twoSpheres());
  auto box = std::make_shared<PolygonMesh>(makeBox(V3(0.5, 0.5, 0.5)));
  ObjectDatabase db;
  db.add("spheres", spheres, test::pose(V3::Zero()), false);
  db.add("box", box, test::pose(V3::Zero()), false);
  const ObjNode &a = db.objects[0];
  ObjNode& b = db.objects[1];
  const V3 centre = worldContainer(a).center();
  std::mt19937 rng(23);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> gap(-0.03, 0.05);  // < 0: overlapping
  int apart = 0, overlappingTried = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const V3 d = test::drawnVector([&] { return g(rng); }).normalized();
    const auto rotation = test::drawnQuaternion([&] { return g(rng); }).normalized().toRotationMatrix();
    const double top = scannedTop(a, d) - d.dot(centre);              // the spheres' reach along d
    const double reach = 0.25 * (rotation.transpose() * d).cwiseAbs().sum();  // the box's, towards them
    const double wanted = gap(rng);
    b.X_WO = test::pose(centre + (top + reach + wanted) * d, rotation);
    double bottom = 1e300;
    for (const V3& v : box->vertices()) bottom = std::min(bottom, d.dot(b.X_WO * v) - d.dot(centre));
    ASSERT_NEAR(bottom - top, wanted, 1e-9);  // the box's centre, and so the centre line, is where planned
    overlappingTried += wanted < 0.0;
    if (separatedAlongCentreLine(a, b, kDefaultContactTolerance)) {
      ++apart;
      EXPECT_GT(bottom - top, kDefaultContactTolerance) << "trial " << trial;
    }
  }
  EXPECT_GT(overlappingTried, 150);
  EXPECT_GT(apart, 200);  // most poses apart by more than the tolerance are proven so
}

}  // namespace
}  // namespace polysim::collision
