// reduceContacts() on pieces given by hand: where the polygon pairs of two stacked boxes
// report the same segment with different normals, the contact takes the normal its
// features admit, not the mean of the pieces'.

#include "collision/contact_reduction.h"

#include <gtest/gtest.h>

#include "collision/shapes.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;

// The edge of `mesh` between the faces whose normals are n0 and n1 (object frame).
int edgeBetween(const PolygonMesh& mesh, const V3& n0, const V3& n1) {
  for (size_t e = 0; e < mesh.edges().size(); ++e) {
    const MeshEdge& edge = mesh.edges()[e];
    if (edge.face0 < 0 || edge.face1 < 0) continue;
    const V3 &a = mesh.facePlane(edge.face0).normal, &b = mesh.facePlane(edge.face1).normal;
    if (((a - n0).norm() < 1e-12 && (b - n1).norm() < 1e-12) || ((a - n1).norm() < 1e-12 && (b - n0).norm() < 1e-12))
      return static_cast<int>(e);
  }
  ADD_FAILURE() << "no such edge";
  return -1;
}

int faceWithNormal(const PolygonMesh& mesh, const V3& n) {
  for (int f = 0; f < mesh.faceCount(); ++f)
    if ((mesh.facePlane(f).normal - n).norm() < 1e-12) return f;
  ADD_FAILURE() << "no such face";
  return -1;
}

Contact line(const V3& normal, Feature a, Feature b) {
  Contact c;
  c.type = ContactType::Line;
  c.normal = normal.normalized();
  c.points = {V3(0.5, -0.5, 0.5), V3(0.5, 0.5, 0.5)};
  c.featureA = a;
  c.featureB = b;
  return c;
}

// Box A resting on box B (unit boxes, A's centre at z = 1, B's at the origin), seen
// along their common +x edge at x = 0.5, z = 0.5: A's side face's bottom edge lies on
// B's top face (normal +z), and A's bottom edge against B's top edge, two parallel
// edges, proposes the bisector of their outward directions, 45 degrees from +z. Only +z
// is admitted by both features of some piece (A's edge touched from below, B's face from
// above); the mean, 22.5 degrees off, is not a contact normal at all.
TEST(ContactReduction, DisagreeingPiecesTakeTheAdmittedNormalNotTheirMean) {
  const PolygonMesh box(makeBox(V3(1, 1, 1)));
  const int edgeA = edgeBetween(box, V3(1, 0, 0), V3(0, 0, -1));  // A's bottom +x edge
  const int edgeB = edgeBetween(box, V3(1, 0, 0), V3(0, 0, 1));   // B's top +x edge
  const int topB = faceWithNormal(box, V3(0, 0, 1));
  const std::vector<Contact> raw = {
      line(V3(0, 0, 1), {Feature::Kind::Edge, edgeA}, {Feature::Kind::Face, topB}),
      line(V3(-1, 0, 1), {Feature::Kind::Edge, edgeA}, {Feature::Kind::Edge, edgeB}),
  };
  const PairGeometry geometry{&box, &box, Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()};
  for (bool reversed : {false, true}) {
    SCOPED_TRACE(reversed ? "pieces reversed" : "pieces in order");
    const std::vector<Contact> pieces = reversed ? std::vector<Contact>{raw[1], raw[0]} : raw;
    const std::vector<Contact> reduced = reduceContacts(pieces, 1e-4, &geometry);
    ASSERT_EQ(reduced.size(), 1u);
    EXPECT_EQ(reduced[0].type, ContactType::Line);
    EXPECT_TRUE(test::near(reduced[0].normal, V3(0, 0, 1), 1e-12));
  }
}

// Pieces whose normals agree within the cone slack keep their mean: no piece is more
// right than another.
TEST(ContactReduction, AgreeingPiecesKeepTheirMeanNormal) {
  const PolygonMesh box(makeBox(V3(1, 1, 1)));
  const int edgeA = edgeBetween(box, V3(1, 0, 0), V3(0, 0, -1));
  const int topB = faceWithNormal(box, V3(0, 0, 1));
  const double tilt = 2e-4;  // rad, within kNormalConeSlack
  const std::vector<Contact> raw = {
      line(V3(0, 0, 1), {Feature::Kind::Edge, edgeA}, {Feature::Kind::Face, topB}),
      line(V3(std::sin(tilt), 0, std::cos(tilt)), {Feature::Kind::Edge, edgeA}, {Feature::Kind::Face, topB}),
  };
  const PairGeometry geometry{&box, &box, Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()};
  const std::vector<Contact> reduced = reduceContacts(raw, 1e-4, &geometry);
  ASSERT_EQ(reduced.size(), 1u);
  EXPECT_TRUE(test::near(reduced[0].normal, V3(std::sin(tilt / 2), 0, std::cos(tilt / 2)), 1e-12));
}

// The same edge on the same face found by two polygon pairs at different depths (a
// vertex 30 um off the face by one, the edge 80 um into it by the other): the joined
// line takes, at each end, the deepest gap along its normal, whichever piece came first.
// With the first piece's gaps the solver would not see the overlap that the next
// intersection test finds too deep.
TEST(ContactReduction, AJoinedLineTakesTheDeepestGapAtEachEnd) {
  const PolygonMesh box(makeBox(V3(1, 1, 1)));
  const int edgeA = edgeBetween(box, V3(1, 0, 0), V3(0, 0, -1));
  const int topB = faceWithNormal(box, V3(0, 0, 1));
  Contact shallow = line(V3(0, 0, 1), {Feature::Kind::Edge, edgeA}, {Feature::Kind::Face, topB});
  shallow.gaps = {3e-5, 3e-5};
  shallow.separation = 3e-5;
  Contact deep = shallow;
  deep.gaps = {-8e-5, -6e-5};
  deep.separation = -8e-5;
  const PairGeometry geometry{&box, &box, Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()};
  for (bool deepFirst : {false, true}) {
    SCOPED_TRACE(deepFirst ? "deep piece first" : "shallow piece first");
    const std::vector<Contact> pieces = deepFirst ? std::vector<Contact>{deep, shallow} : std::vector<Contact>{shallow, deep};
    const std::vector<Contact> reduced = reduceContacts(pieces, 1e-4, &geometry);
    ASSERT_EQ(reduced.size(), 1u);
    ASSERT_EQ(reduced[0].points.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
      const double expected = reduced[0].points[i].y() < 0 ? -8e-5 : -6e-5;
      EXPECT_DOUBLE_EQ(reduced[0].gapAt(i), expected) << "end " << i;
    }
    EXPECT_DOUBLE_EQ(reduced[0].separation, -8e-5);
  }
}

}  // namespace
}  // namespace polysim::collision
