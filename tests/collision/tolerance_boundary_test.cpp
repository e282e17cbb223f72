// The verdicts exactly at the tolerance, where SPEC.md's words decide: a feature
// "more than epsilon" inside the other interpenetrates, and features "within epsilon"
// of each other are in contact. The cases use epsilon = 2^-13 and poses whose
// coordinates are short binary fractions, so that every distance is computed exactly:
// a box sunk by exactly epsilon is in contact, one sunk by one part in 2^20 more is not.

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace polysim::collision
