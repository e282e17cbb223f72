// The verdicts exactly at the tolerance, where SPEC.md's words decide: a feature
// "more than epsilon" inside the other interpenetrates, and features "within epsilon"
// of each other are in contact. The cases use epsilon = 2^-13 and poses whose
// coordinates are short binary fractions, so that every distance is computed exactly:
// a box sunk by exactly epsilon is in contact, one sunk by one part in 2^20 more is not.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "collision/intersection.h"
#include "collision/shapes.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using test::pose;
using V3 = Eigen::Vector3d;

constexpr double kEps = 1.0 / 8192;           // 2^-13 m: exact in binary
constexpr double kJustOver = kEps / 1048576;  // 2^-33 m: one part in 2^20 of epsilon

struct Floor {
  const char* name;
  MeshData mesh;
  Eigen::Isometry3d X;  // the floor's top face at z = 0
};

std::vector<Floor> floors() {
  return {{"box_floor", makeBox(V3(8, 8, 1)), pose(V3(0, 0, -0.5))},
          {"triangulated_floor", makeTriangulatedFloor(8, 8, 8), pose(V3::Zero())}};
}

// Frames that keep every coordinate exact: the identity and translations by short
// binary fractions (a rotation would round the distances).
std::vector<test::NamedFrame> exactFrames() {
  return {{"identity", Eigen::Isometry3d::Identity()},
          {"translated", pose(V3(3.25, -2.5, 7.125))},
          {"translated_far", pose(V3(-64.5, 128.25, -16.0))}};
}

// The status of a unit box whose bottom face lies `height` above the floor's top (a
// negative height: sunk into it), in every exact frame and with the objects swapped.
// Fails the test unless every one gives `expected`.
void expectStatus(double height, Status expected) {
  for (const Floor& floor : floors())
    for (const test::NamedFrame& frame : exactFrames())
      for (bool swapped : {false, true}) {
        SCOPED_TRACE(std::string(floor.name) + " in frame " + frame.name + (swapped ? ", swapped" : ""));
        ObjectDatabase db;
        db.tolerance = kEps;
        auto box = std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1)));
        auto ground = std::make_shared<PolygonMesh>(floor.mesh);
        const Eigen::Isometry3d X_box = frame.X * pose(V3(0.25, -0.125, 0.5 + height));
        if (swapped) db.add("floor", ground, frame.X * floor.X, true);
        db.add("box", box, X_box, false);
        if (!swapped) db.add("floor", ground, frame.X * floor.X, true);
        const IntersectionResult r = test4Intersection(db);
        EXPECT_EQ(toString(r.status), toString(expected)) << "height " << height;
        if (expected != Status::Contact || r.pairs.size() != 1) continue;
        // Within the band the box's bottom face is one area contact, the whole face.
        const std::vector<Contact>& contacts = r.pairs[0].contacts;
        ASSERT_EQ(contacts.size(), 1u) << "height " << height;
        EXPECT_EQ(toString(contacts[0].type), "area") << "height " << height;
        EXPECT_EQ(contacts[0].points.size(), 4u) << "height " << height;
      }
}

TEST(ToleranceBoundary, SunkByExactlyEpsilonIsContact) { expectStatus(-kEps, Status::Contact); }

TEST(ToleranceBoundary, SunkByJustMoreThanEpsilonInterpenetrates) {
  expectStatus(-kEps - kJustOver, Status::Interpenetrating);
}

TEST(ToleranceBoundary, ExactlyEpsilonApartIsContact) { expectStatus(kEps, Status::Contact); }

TEST(ToleranceBoundary, JustMoreThanEpsilonApartIsSeparate) { expectStatus(kEps + kJustOver, Status::Separate); }

// Two boxes side by side, the same rule across a vertical face pair and for the
// depth of one box's cut through the other's face (the edges overhang).
TEST(ToleranceBoundary, BoxesSideBySideDecidedAtEpsilon) {
  auto box = std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1)));
  struct Gap {
    double gap;
    Status expected;
  };
  for (const Gap& g : {Gap{-kEps, Status::Contact}, Gap{-kEps - kJustOver, Status::Interpenetrating},
                       Gap{kEps, Status::Contact}, Gap{kEps + kJustOver, Status::Separate}})
    for (double sideways : {0.0, 0.5}) {  // face on face; half the face overhanging
      ObjectDatabase db;
      db.tolerance = kEps;
      db.add("left", box, pose(V3::Zero()), false);
      db.add("right", box, pose(V3(1 + g.gap, sideways, 0.25)), false);
      EXPECT_EQ(toString(test4Intersection(db).status), toString(g.expected))
          << "gap " << g.gap << ", shifted " << sideways;
    }
}

// A square pyramid standing on its apex (apex at the origin, base the square |x|, |y|
// <= 1 at z = 1) and a wedge lying on its edge (the edge along x at the origin, the top
// face at z = 1): exact coordinates, so a single vertex or a single edge can be placed
// exactly eps above the floor.
MeshData apexDownPyramid() {
  MeshData m;
  m.vertices = {V3(0, 0, 0), V3(1, 1, 1), V3(-1, 1, 1), V3(-1, -1, 1), V3(1, -1, 1)};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {0, 4, 3}, {0, 1, 4}, {1, 2, 3, 4}};
  return m;
}

MeshData edgeDownWedge() {
  MeshData m;
  m.vertices = {V3(-1, 0, 0), V3(1, 0, 0), V3(-1, 1, 1), V3(1, 1, 1), V3(-1, -1, 1), V3(1, -1, 1)};
  m.faces = {{2, 3, 1, 0}, {1, 5, 4, 0}, {4, 5, 3, 2}, {4, 2, 0}, {3, 5, 1}};  // outward: counter-clockwise seen from outside
  return m;
}

// The status and contact types of `mesh` (posed so its lowest feature is at z = 0) raised
// by `height` over the box floor, in every exact frame and swapped.
void expectFeatureStatus(const MeshData& mesh, double height, Status expected, ContactType type) {
  const Floor floor = floors()[0];
  for (const test::NamedFrame& frame : exactFrames())
    for (bool swapped : {false, true}) {
      SCOPED_TRACE(std::string("frame ") + frame.name + (swapped ? ", swapped" : "") + ", height " +
                   std::to_string(height / kEps) + " eps");
      ObjectDatabase db;
      db.tolerance = kEps;
      auto body = std::make_shared<PolygonMesh>(mesh);
      auto ground = std::make_shared<PolygonMesh>(floor.mesh);
      if (swapped) db.add("floor", ground, frame.X * floor.X, true);
      db.add("body", body, frame.X * pose(V3(0.25, -0.125, height)), false);
      if (!swapped) db.add("floor", ground, frame.X * floor.X, true);
      const IntersectionResult r = test4Intersection(db);
      EXPECT_EQ(toString(r.status), toString(expected));
      if (expected != Status::Contact || r.pairs.size() != 1) continue;
      ASSERT_EQ(r.pairs[0].contacts.size(), 1u);
      EXPECT_EQ(toString(r.pairs[0].contacts[0].type), toString(type));
    }
}

TEST(ToleranceBoundary, VertexExactlyEpsilonAboveAFaceIsAPointContact) {
  expectFeatureStatus(apexDownPyramid(), kEps, Status::Contact, ContactType::Point);
  expectFeatureStatus(apexDownPyramid(), kEps + kJustOver, Status::Separate, ContactType::Point);
  expectFeatureStatus(apexDownPyramid(), -kEps, Status::Contact, ContactType::Point);
}

TEST(ToleranceBoundary, EdgeExactlyEpsilonAboveAFaceIsALineContact) {
  expectFeatureStatus(edgeDownWedge(), kEps, Status::Contact, ContactType::Line);
  expectFeatureStatus(edgeDownWedge(), kEps + kJustOver, Status::Separate, ContactType::Line);
  expectFeatureStatus(edgeDownWedge(), -0.5 * kEps, Status::Contact, ContactType::Line);
}

// An edge between two faces at 45 degrees to the floor, sunk by d: in contact up to
// d = eps, on either floor. Against a box the pair's penetration depth decides; against a
// triangulated plane (no convex solid) the polygons' own measure, which must read the
// same d. It used to read sqrt(2) d: the floor face's cut through a slanted face lies
// sqrt(2) d from the sharp edge along that face, and the depth behind that face alone
// ignored the other face of the edge's wedge.
TEST(ToleranceBoundary, EdgeSunkIntoAFaceIsContactUpToEpsilonOnBoxAndMeshFloors) {
  for (const Floor& floor : floors())
    for (double sunk : {0.5 * kEps, 0.75 * kEps, 0.9 * kEps, kEps + kJustOver}) {
      SCOPED_TRACE(std::string(floor.name) + ", sunk " + std::to_string(sunk / kEps) + " eps");
      ObjectDatabase db;
      db.tolerance = kEps;
      db.add("wedge", std::make_shared<PolygonMesh>(edgeDownWedge()), pose(V3(0.25, -0.125, -sunk)), false);
      db.add("floor", std::make_shared<PolygonMesh>(floor.mesh), floor.X, true);
      const IntersectionResult r = test4Intersection(db);
      ASSERT_EQ(r.pairs.size(), 1u);
      EXPECT_EQ(toString(r.status), sunk > kEps ? "interpenetrating" : "contact");
      if (sunk > kEps) {
        EXPECT_NEAR(r.pairs[0].depth, sunk, 1e-11);
      } else {
        ASSERT_EQ(r.pairs[0].contacts.size(), 1u);
        EXPECT_EQ(toString(r.pairs[0].contacts[0].type), "line");
        EXPECT_NEAR(r.pairs[0].contacts[0].separation, -sunk, 1e-12);
      }
    }
}

// A box tilted across another box's top edge, that edge sunk by d into its bottom face
// (a box tipping over the edge of the one below it, as in any pile). The contact is a
// line with gap -d along the tilted face's normal, and the pair interpenetrates only once
// d passes eps. The polygons' own measure read it deeper (along the lower box's top
// normal, over its face grown by eps: eps tan(tilt) more), so a state the solver held
// within the band was judged interpenetrating, and a pile's island stalled on it.
TEST(ToleranceBoundary, BoxTiltedAcrossAnotherBoxsEdgeInterpenetratesOnlyOnceItsGapPassesEpsilon) {
  const auto cube = std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1)));
  for (double tilt : {0.05, 0.17, 0.5})
    for (double sunk : {0.0, 0.5 * kEps, 0.9 * kEps, kEps, kEps + 64 * kJustOver}) {
      SCOPED_TRACE("tilt " + std::to_string(tilt) + " rad, sunk " + std::to_string(sunk / kEps) + " eps");
      // The upper box's bottom face rises over the lower box (towards -x) and passes its
      // edge at x = 0.5, z = 0.5 a fifth of the face beyond it.
      const Eigen::Matrix3d R = Eigen::AngleAxisd(tilt, V3::UnitY()).toRotationMatrix();
      const V3 bottomNormal = R * V3(0, 0, -1);  // out of the upper box
      const V3 faceCentre = V3(0.5, 0, 0.5) + R * V3(-0.3, 0, 0) + sunk * bottomNormal;
      ObjectDatabase db;
      db.tolerance = kEps;
      db.add("upper", cube, pose(faceCentre - 0.5 * bottomNormal, R), false);
      db.add("lower", cube, pose(V3::Zero()), false);
      const IntersectionResult r = test4Intersection(db);
      ASSERT_EQ(r.pairs.size(), 1u);
      if (sunk > kEps) {
        EXPECT_EQ(toString(r.status), "interpenetrating");
        EXPECT_NEAR(r.pairs[0].depth, sunk, 1e-12);
        continue;
      }
      EXPECT_EQ(toString(r.status), "contact");
      ASSERT_EQ(r.pairs[0].contacts.size(), 1u);
      const Contact& c = r.pairs[0].contacts[0];
      EXPECT_EQ(toString(c.type), "line");
      EXPECT_NEAR(c.separation, -sunk, 1e-12);
      EXPECT_NEAR(std::abs(c.normal.dot(bottomNormal)), 1.0, 1e-12);
    }
}

// A floor of two squares, the right one a quarter tolerance lower: they are not one flat
// patch, so the box's face is judged against the second square on its own (not as part
// of the first one's patch). With the box's bottom 3/4 eps above the left square it is
// exactly eps above the right one: both halves are area contacts, half the face each.
// Both orders of the floor's faces, so that either square is the one judged alone.
TEST(ToleranceBoundary, FaceExactlyEpsilonAboveTheSecondOfTwoLevelsIsAnArea) {
  const double step = kEps / 4;
  for (bool leftFirst : {true, false}) {
    MeshData floor;
    floor.vertices = {V3(-2, -1, 0), V3(0, -1, 0), V3(0, 1, 0), V3(-2, 1, 0),
                      V3(0, -1, -step), V3(2, -1, -step), V3(2, 1, -step), V3(0, 1, -step)};
    floor.faces = {{0, 1, 2, 3}, {4, 5, 6, 7}};
    if (!leftFirst) std::swap(floor.faces[0], floor.faces[1]);
    for (double extra : {0.0, kJustOver}) {
      SCOPED_TRACE(std::string(leftFirst ? "left" : "right") + " square first, " + (extra > 0 ? "just over" : "exactly"));
      ObjectDatabase db;
      db.tolerance = kEps;
      db.add("box", std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1))), pose(V3(0, 0, 0.5 + 0.75 * kEps + extra)),
             false);
      db.add("floor", std::make_shared<PolygonMesh>(floor), Eigen::Isometry3d::Identity(), true);
      const IntersectionResult r = test4Intersection(db);
      ASSERT_EQ(toString(r.status), "contact");
      double area = 0.0;
      for (const Contact& c : r.pairs[0].contacts)
        if (c.type == ContactType::Area) {
          V3 twice = V3::Zero();
          for (size_t i = 0; i < c.points.size(); ++i) twice += c.points[i].cross(c.points[(i + 1) % c.points.size()]);
          area += 0.5 * std::abs(twice.z());
        }
      // Exactly eps above the right square: both halves; just over: the left half only.
      EXPECT_NEAR(area, extra > 0 ? 0.5 : 1.0, 1e-9);
    }
  }
}

}  // namespace
}  // namespace polysim::collision
