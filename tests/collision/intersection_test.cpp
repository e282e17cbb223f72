// test4Intersection() on hand-derived cases, each under several world frames and with
// the two objects swapped (same contacts, flipped normals).

#include "collision/intersection.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "collision/polygon_tests.h"
#include "collision/shapes.h"
#include "collision/tolerances.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using test::pose;
using test::rot;
using V3 = Eigen::Vector3d;

constexpr double kEps = kDefaultContactTolerance;

struct ExpectedContact {
  ContactType type;
  V3 normal;       // from B towards A
  double measure;  // area (m^2) of an area, length (m) of a line, 0 for a point
  V3 centroid;     // mean of the contact's points
};

struct Case {
  std::string name;
  MeshData meshA, meshB;
  Eigen::Isometry3d X_A, X_B;
  bool bStatic;
  Status status;
  std::vector<ExpectedContact> contacts;
};

double measure(const Contact& c) {
  if (c.type == ContactType::Line) return (c.points[1] - c.points[0]).norm();
  if (c.type == ContactType::Point) return 0.0;
  V3 twice = V3::Zero();
  for (size_t i = 0; i < c.points.size(); ++i) twice += c.points[i].cross(c.points[(i + 1) % c.points.size()]);
  return 0.5 * twice.dot(c.normal);  // positive when counter-clockwise about the normal
}

V3 centroid(const Contact& c) {
  V3 sum = V3::Zero();
  for (const V3& p : c.points) sum += p;
  return sum / static_cast<double>(c.points.size());
}

const MeshData kUnitBox = makeBox(V3(1, 1, 1));
const MeshData kFloorBox = makeBox(V3(10, 10, 1));
const Eigen::Isometry3d kFloorPose = pose(V3(0, 0, -0.5));
const double kOctagonArea = 2 * (std::sqrt(2.0) - 1);

// The rotation that turns the box's (1,1,1) corner straight down.
Eigen::Matrix3d cornerDown() {
  return Eigen::Quaterniond::FromTwoVectors(V3(1, 1, 1).normalized(), V3(0, 0, -1)).toRotationMatrix();
}

// A unit box turned by `angle` about y with its +x bottom edge on x = 0.5, z = 0.5.
Eigen::Isometry3d tiltedOntoEdge(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return pose(V3(0.5 - 0.5 * (c - s), 0, 0.5 + 0.5 * (s + c)), rot(angle, V3::UnitY()));
}

std::vector<Case> cases() {
  const double r2 = std::sqrt(2.0);
  return {
      {"face_on_face", kUnitBox, kUnitBox, pose(V3(0, 0, 1)), pose(V3::Zero()), false, Status::Contact,
       {{ContactType::Area, V3(0, 0, 1), 1.0, V3(0, 0, 0.5)}}},
      {"turned_45_octagon", kUnitBox, kUnitBox, pose(V3(0, 0, 1), rot(M_PI / 4, V3::UnitZ())), pose(V3::Zero()), false,
       Status::Contact, {{ContactType::Area, V3(0, 0, 1), kOctagonArea, V3(0, 0, 0.5)}}},
      {"box_on_edge", kUnitBox, kFloorBox, pose(V3(0, 0, r2 / 2), rot(M_PI / 4, V3::UnitX())), kFloorPose, true,
       Status::Contact, {{ContactType::Line, V3(0, 0, 1), 1.0, V3(0, 0, 0)}}},
      {"box_on_vertex", kUnitBox, kFloorBox, pose(V3(0, 0, std::sqrt(3.0) / 2), cornerDown()), kFloorPose, true,
       Status::Contact, {{ContactType::Point, V3(0, 0, 1), 0.0, V3(0, 0, 0)}}},
      {"edges_crossing", kUnitBox, kUnitBox, pose(V3(0, 0, r2), rot(M_PI / 4, V3::UnitX())),
       pose(V3::Zero(), rot(M_PI / 4, V3::UnitY())), false, Status::Contact,
       {{ContactType::Point, V3(0, 0, 1), 0.0, V3(0, 0, r2 / 2)}}},
      {"gap_half_tolerance", kUnitBox, kUnitBox, pose(V3(0, 0, 1 + kEps / 2)), pose(V3::Zero()), false,
       Status::Contact, {{ContactType::Area, V3(0, 0, 1), 1.0, V3(0, 0, 0.5 + kEps / 4)}}},
      {"ten_tolerances_apart", kUnitBox, kUnitBox, pose(V3(0, 0, 1 + 10 * kEps)), pose(V3::Zero()), false,
       Status::Separate, {}},
      {"ten_tolerances_deep", kUnitBox, kUnitBox, pose(V3(0, 0, 1 - 10 * kEps)), pose(V3::Zero()), false,
       Status::Interpenetrating, {}},
      {"staple_two_feet", test::makeStaple(), kFloorBox, pose(V3(-1.5, -0.5, 0)), kFloorPose, true, Status::Contact,
       {{ContactType::Area, V3(0, 0, 1), 1.0, V3(-1, 0, 0)}, {ContactType::Area, V3(0, 0, 1), 1.0, V3(1, 0, 0)}}},
      {"hexagon_face", test::makeHexPrism(1.0, 1.0), kFloorBox, pose(V3(0, 0, 0.5)), kFloorPose, true,
       Status::Contact, {{ContactType::Area, V3(0, 0, 1), 1.5 * std::sqrt(3.0), V3(0, 0, 0)}}},
      // A triangulated floor whose grid lines run along the box's sides: one square.
      {"box_on_triangulated_floor", kUnitBox, makeTriangulatedFloor(10, 10, 10), pose(V3(0, 0, 0.5)),
       pose(V3::Zero()), true, Status::Contact, {{ContactType::Area, V3(0, 0, 1), 1.0, V3(0, 0, 0)}}},
      // Grid lines cross the box's sides mid-cell and the triangles' diagonals run through
      // two of its corners: triangles that only touch the face add nothing (area_on_patch.h).
      {"corners_on_triangle_diagonals", kUnitBox, makeTriangulatedFloor(10, 10, 50),
       pose(V3(0.05, 0.05, 0.5 - kEps / 2)), pose(V3::Zero()), true, Status::Contact,
       {{ContactType::Area, V3(0, 0, 1), 1.0, V3(0.05, 0.05, -kEps / 4)}}},
      // A quarter of the box hangs over the floor's edge at x = 3: the pieces do not cover
      // the face, and the reduction merges them into the overlap.
      {"overhanging_triangulated_floor", kUnitBox, makeTriangulatedFloor(6, 6, 12), pose(V3(2.75, 0, 0.5)),
       pose(V3::Zero()), true, Status::Contact, {{ContactType::Area, V3(0, 0, 1), 0.75, V3(2.625, 0, 0)}}},
      {"edge_along_triangle_edges", kUnitBox, makeTriangulatedFloor(10, 10, 10),
       pose(V3(0.5, 0, r2 / 2), rot(M_PI / 4, V3::UnitX())), pose(V3::Zero()), true, Status::Contact,
       {{ContactType::Line, V3(0, 0, 1), 1.0, V3(0.5, 0, 0)}}},
      {"sunk_into_triangulated_floor", kUnitBox, makeTriangulatedFloor(10, 10, 10), pose(V3(0, 0, 0.5 - 10 * kEps)),
       pose(V3::Zero()), true, Status::Interpenetrating, {}},
      // Half the top box hangs over the edge, sunk by half the tolerance: contact only.
      {"overhang_within_tolerance", kUnitBox, kUnitBox, pose(V3(0.5, 0, 1 - kEps / 2)), pose(V3::Zero()), false,
       Status::Contact, {{ContactType::Area, V3(0, 0, 1), 0.5, V3(0.25, 0, 0.5 - kEps / 4)}}},
      // Side by side at exactly the same height, pushed 0.3 into each other.
      {"aligned_side_by_side_overlap", kUnitBox, kUnitBox, pose(V3(0.7, 0, 0)), pose(V3::Zero()), false,
       Status::Interpenetrating, {}},
      // The top box turned about y by four tolerances onto its +x bottom edge, which lies
      // on the lower box's top edge: one line with the top face's normal. The side faces
      // meeting there must not tilt it (they did: 45 degrees, and a 10-box stack fell).
      {"tilted_onto_coincident_edge", kUnitBox, kUnitBox, tiltedOntoEdge(4 * kEps), pose(V3::Zero()), false,
       Status::Contact, {{ContactType::Line, V3(0, 0, 1), 1.0, V3(0.5, 0, 0.5)}}},
      // A box on its edge, the edge tilted so that its ends lie 0.6 eps above and below
      // the floor: one line, the edge's length across, though the edge is not square to
      // the normal within eps (its ends differ by 1.2 eps: the cone's slack admits it).
      // Each end of the line lies midway between the edge's end and the floor, so the line
      // rises half as steeply as the edge.
      {"edge_dipping_through_the_band", kUnitBox, kFloorBox,
       pose(V3(r2 / 2 * std::sin(1.2 * kEps), 0, r2 / 2 * std::cos(1.2 * kEps)),
            rot(1.2 * kEps, V3::UnitY()) * rot(M_PI / 4, V3::UnitX())),
       kFloorPose, true, Status::Contact,
       {{ContactType::Line, V3(0, 0, 1), std::hypot(std::cos(1.2 * kEps), 0.5 * std::sin(1.2 * kEps)), V3(0, 0, 0)}}},
      {"aligned_side_by_side_touching", kUnitBox, kUnitBox, pose(V3(1, 0, 0)), pose(V3::Zero()), false,
       Status::Contact, {{ContactType::Area, V3(1, 0, 0), 1.0, V3(0.5, 0, 0)}}},
  };
}

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class IntersectionCase : public ::testing::TestWithParam<Case> {};

void checkCase(const Case& c, const test::NamedFrame& frame, bool swapped) {
  SCOPED_TRACE(c.name + " in frame " + frame.name + (swapped ? ", swapped" : ""));
  ObjectDatabase db;
  db.tolerance = kEps;
  auto meshA = std::make_shared<PolygonMesh>(c.meshA);
  auto meshB = std::make_shared<PolygonMesh>(c.meshB);
  if (swapped) {
    db.add("B", meshB, frame.X * c.X_B, c.bStatic);
    db.add("A", meshA, frame.X * c.X_A, false);
  } else {
    db.add("A", meshA, frame.X * c.X_A, false);
    db.add("B", meshB, frame.X * c.X_B, c.bStatic);
  }
  const IntersectionResult r = test4Intersection(db);
  ASSERT_EQ(toString(r.status), toString(c.status));
  if (c.status == Status::Separate) {
    EXPECT_TRUE(r.pairs.empty());
    return;
  }
  ASSERT_EQ(r.pairs.size(), 1u);
  const PairResult& pair = r.pairs[0];
  if (c.status == Status::Interpenetrating) {
    EXPECT_GT(pair.depth, kEps);
    return;
  }
  ASSERT_EQ(pair.contacts.size(), c.contacts.size());
  // Where an edge of each box lies on the other's face, either face's normal is true: they
  // differ by the tilt, and which one is reported depends on the order.
  const double normalTolerance = c.name == "tilted_onto_coincident_edge" ? 4 * kEps : 1e-9;
  for (const ExpectedContact& e : c.contacts) {
    // A static object is always `b`, so swapping only flips the normal of moving pairs.
    const bool flipped = swapped && !c.bStatic;
    const V3 normal = (flipped ? -1.0 : 1.0) * (frame.X.linear() * e.normal);
    const V3 where = frame.X * e.centroid;
    const Contact* match = nullptr;
    for (const Contact& got : pair.contacts)
      if (got.type == e.type && (centroid(got) - where).norm() < 1e-6) match = &got;
    ASSERT_NE(match, nullptr) << "no " << toString(e.type) << " contact at " << where.transpose();
    EXPECT_TRUE(test::near(match->normal, normal, normalTolerance));
    EXPECT_NEAR(measure(*match), e.measure, 1e-9);
    EXPECT_LE(std::abs(match->separation), kEps);
  }
}

TEST_P(IntersectionCase, SameContactsInEveryFrameAndOrder) {
  for (const test::NamedFrame& frame : test::worldFrames()) {
    checkCase(GetParam(), frame, false);
    checkCase(GetParam(), frame, true);
  }
}

INSTANTIATE_TEST_SUITE_P(HandDerived, IntersectionCase, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

TEST(Intersection, OctagonHasEightCornersOnTheUnitSquares) {
  ObjectDatabase db;
  db.add("A", std::make_shared<PolygonMesh>(kUnitBox), pose(V3(0, 0, 1), rot(M_PI / 4, V3::UnitZ())), false);
  db.add("B", std::make_shared<PolygonMesh>(kUnitBox), pose(V3::Zero()), false);
  const IntersectionResult r = test4Intersection(db);
  ASSERT_EQ(r.pairs.size(), 1u);
  ASSERT_EQ(r.pairs[0].contacts.size(), 1u);
  const Contact& c = r.pairs[0].contacts[0];
  ASSERT_EQ(c.points.size(), 8u);
  for (const V3& p : c.points) {
    // Every corner lies on the boundary of both squares: the axis one and the turned one.
    const V3 q = rot(-M_PI / 4, V3::UnitZ()) * p;
    EXPECT_NEAR(p.head<2>().cwiseAbs().maxCoeff(), 0.5, 1e-9);
    EXPECT_NEAR(q.head<2>().cwiseAbs().maxCoeff(), 0.5, 1e-9);
  }
}

TEST(Intersection, StaticPairsAreNeverTested) {
  ObjectDatabase db;
  db.add("floor", std::make_shared<PolygonMesh>(kFloorBox), kFloorPose, true);
  db.add("wall", std::make_shared<PolygonMesh>(kFloorBox), pose(V3(0, 0, -0.7)), true);  // overlapping
  const IntersectionResult r = test4Intersection(db);
  EXPECT_EQ(r.status, Status::Separate);
  EXPECT_EQ(r.polygonPairsTested, 0);
}

// The containers are padded by the tolerance the objects were added with; the overlap
// region grows them by the database's tolerance when judging, so raising the tolerance
// afterwards (as a caller tuning it may) still finds every pair within the new band.
TEST(Intersection, ToleranceRaisedAfterTheObjectsWereAddedStillFindsTheContact) {
  ObjectDatabase db;
  db.tolerance = 1e-4;
  db.add("box", std::make_shared<PolygonMesh>(kUnitBox), pose(V3(0, 0, 0.5 + 5e-4)), false);
  db.add("floor", std::make_shared<PolygonMesh>(kFloorBox), kFloorPose, true);
  EXPECT_EQ(test4Intersection(db).status, Status::Separate);  // 0.5 mm apart: beyond 0.1 mm
  db.tolerance = 1e-3;
  const IntersectionResult r = test4Intersection(db);
  EXPECT_EQ(r.status, Status::Contact);  // within 1 mm
  ASSERT_EQ(r.pairs.size(), 1u);
  ASSERT_EQ(r.pairs[0].contacts.size(), 1u);
  EXPECT_NEAR(r.pairs[0].contacts[0].separation, 5e-4, 1e-12);
}

TEST(Intersection, StopAtInterpenetrationSkipsTheRest) {
  ObjectDatabase db;
  db.add("A", std::make_shared<PolygonMesh>(kUnitBox), pose(V3(0, 0, 0.5)), false);
  db.add("B", std::make_shared<PolygonMesh>(kUnitBox), pose(V3::Zero()), false);
  IntersectionOptions quick;
  quick.contacts = false;
  quick.stopAtInterpenetration = true;
  const IntersectionResult fast = test4Intersection(db, quick);
  const IntersectionResult full = test4Intersection(db);
  EXPECT_EQ(fast.status, Status::Interpenetrating);
  EXPECT_EQ(full.status, Status::Interpenetrating);
  EXPECT_TRUE(fast.pairs[0].contacts.empty());
  EXPECT_NEAR(full.pairs[0].depth, 0.5, 1e-9);
}

// A workspace tested again and again reuses its pool of emptied contacts and does not
// grow it: a box on a floor is an area contact (AreaOnPatch::finish), which once built
// its own buffers and was recycled into the pool at the next test, one more each time;
// a refilled pile so grew for good. The pool is bounded besides (kMaxSpareContacts).
TEST(Intersection, RepeatedTestsKeepTheSpareContactsBounded) {
  ObjectDatabase db;
  db.add("floor", std::make_shared<PolygonMesh>(kFloorBox), kFloorPose, true);
  for (int k = 0; k < 3; ++k)
    db.add("box" + std::to_string(k), std::make_shared<PolygonMesh>(kUnitBox), pose(V3(2.0 * k, 0, 0.5), rot(0.3 * k, V3::UnitZ())), false);
  IntersectionWorkspace ws;
  for (int call = 0; call < 3; ++call) ASSERT_EQ(test4Intersection(db, ws).pairs.size(), 3u);
  const size_t warmedUp = ws.scratch.spare.size();
  for (int call = 0; call < 100; ++call) {
    ASSERT_EQ(test4Intersection(db, ws).pairs.size(), 3u);
    ASSERT_LE(ws.scratch.spare.size(), warmedUp) << "call " << call;
  }
  std::vector<Contact> many(2 * kMaxSpareContacts);
  recycleContacts(many, ws.scratch);
  EXPECT_TRUE(many.empty());
  EXPECT_EQ(ws.scratch.spare.size(), kMaxSpareContacts);
}

}  // namespace
}  // namespace polysim::collision
