// appendContactPoints(): a pair's contacts that share a plane are one manifold for the
// solver, the corners of the convex hull of their points.

#include "sim/contact_points.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>

#include "collision/intersection.h"
#include "collision/polygon_mesh.h"
#include "collision/shapes.h"
#include "tests/poses.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

using collision::Contact;
using collision::ContactType;
using collision::Feature;
using Eigen::Vector3d;

Contact contactOf(ContactType type, const Vector3d& normal, const std::vector<Vector3d>& points,
                  const std::vector<double>& gaps, Feature::Kind onA = Feature::Kind::Face,
                  Feature::Kind onB = Feature::Kind::Face) {
  Contact c;
  c.type = type;
  c.normal = normal.normalized();
  for (size_t i = 0; i < points.size(); ++i) c.addPoint(points[i], gaps[i]);
  c.featureA.kind = onA;
  c.featureB.kind = onB;
  return c;
}

std::vector<dynamics::ContactPoint> pointsOf(const std::vector<Contact>& contacts) {
  std::vector<dynamics::ContactPoint> out;
  appendContactPoints(1, 2, contacts, {0.0, 0.5}, out);
  return out;
}

// The manifolds of `points`, by id: how many points each has.
std::map<int, int> manifoldSizes(const std::vector<dynamics::ContactPoint>& points) {
  std::map<int, int> sizes;
  for (const dynamics::ContactPoint& p : points) ++sizes[p.manifold];
  return sizes;
}

// A box resting on three corners reports two edges on the floor that share a corner. The
// corner is one point, with the deeper of its two gaps, and the three corners one block.
TEST(ContactPoints, TwoEdgesSharingACornerAreOneManifoldWithTheCornerOnce) {
  const Vector3d up = Vector3d::UnitZ();
  const std::vector<dynamics::ContactPoint> out =
      pointsOf({contactOf(ContactType::Line, up, {{0, 0, 0}, {1, 0, 0}}, {-1e-5, -2e-5}),
                contactOf(ContactType::Line, up, {{1, 0, 0}, {1, 1, 0}}, {-5e-5, 3e-5})});
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(manifoldSizes(out).size(), 1u);
  for (const dynamics::ContactPoint& p : out) {
    EXPECT_EQ(p.a, 1);
    EXPECT_EQ(p.b, 2);
    EXPECT_DOUBLE_EQ(p.friction, 0.5);
    if ((p.point - Vector3d(1, 0, 0)).norm() < 1e-12) {
      EXPECT_DOUBLE_EQ(p.separation, -5e-5);
    }
  }
}

// Contacts whose normals differ by more than kCoplanarContactAngle stay apart: a cup's
// wall and its rim, two faces of a box.
TEST(ContactPoints, ContactsOnDifferentPlanesStayApart) {
  const double tilt = 3 * kCoplanarContactAngle;
  const std::vector<dynamics::ContactPoint> out =
      pointsOf({contactOf(ContactType::Line, Vector3d::UnitZ(), {{0, 0, 0}, {1, 0, 0}}, {0, 0}),
                contactOf(ContactType::Line, Vector3d(std::sin(tilt), 0, std::cos(tilt)), {{0, 1, 0}, {1, 1, 0}}, {0, 0}),
                contactOf(ContactType::Point, Vector3d::UnitX(), {{2, 0, 0.5}}, {0})});
  EXPECT_EQ(out.size(), 5u);
  EXPECT_EQ(manifoldSizes(out).size(), 3u);
}

// A group takes its deepest contact's normal; a face of a and a face of b together turn
// between the two bodies, while contacts that agree keep their own rule.
TEST(ContactPoints, AGroupTakesItsDeepestNormalAndTurnsBetweenDisagreeingFaces) {
  const double tilt = 0.3 * kCoplanarContactAngle;
  const Vector3d shallow = Vector3d::UnitZ(), deep = Vector3d(std::sin(tilt), 0, std::cos(tilt));
  const Feature::Kind face = Feature::Kind::Face, vertex = Feature::Kind::Vertex;
  std::vector<dynamics::ContactPoint> out =
      pointsOf({contactOf(ContactType::Point, shallow, {{0, 0, 0}}, {-1e-5}, face, vertex),
                contactOf(ContactType::Point, deep, {{1, 0, 0}}, {-4e-5}, vertex, face)});
  ASSERT_EQ(out.size(), 2u);
  for (const dynamics::ContactPoint& p : out) {
    EXPECT_TRUE(test::near(p.normal, deep, 1e-15));
    EXPECT_DOUBLE_EQ(p.normalTurnWithA, 0.5);
  }
  out = pointsOf({contactOf(ContactType::Point, shallow, {{0, 0, 0}}, {-1e-5}, face, vertex),
                  contactOf(ContactType::Point, deep, {{1, 0, 0}}, {-4e-5}, face, vertex)});
  for (const dynamics::ContactPoint& p : out) EXPECT_DOUBLE_EQ(p.normalTurnWithA, 1.0);
}

// Random coplanar contacts (points, lines, areas) at random poses: every output point is
// an input point with its own gap (or the deepest of its copies), no two coincide, and
// every input point lies inside the output's hull. Checked against a direct test: for
// each output edge, no input point lies outside it.
TEST(ContactPoints, TheManifoldIsTheHullOfTheGroupsPoints) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const Eigen::Quaterniond q(unit(random), unit(random), unit(random), unit(random));
    const Eigen::Isometry3d X = test::pose(Vector3d(unit(random), unit(random), unit(random)), q.normalized().toRotationMatrix());
    const Vector3d n = X.linear() * Vector3d::UnitZ();
    std::vector<Contact> contacts;
    std::vector<Vector3d> all;
    const int count = 2 + trial % 4;
    for (int c = 0; c < count; ++c) {
      const int size = 1 + static_cast<int>(random() % 5);
      std::vector<Vector3d> points;
      std::vector<double> gaps;
      for (int k = 0; k < size; ++k) {
        // Some on a grid, so that copies and collinear points occur.
        const Vector3d local = trial % 3 == 0 ? Vector3d(std::round(2 * unit(random)), std::round(2 * unit(random)), 0)
                                              : Vector3d(unit(random), unit(random), 0);
        points.push_back(X * local);
        gaps.push_back(1e-5 * unit(random));
        all.push_back(points.back());
      }
      contacts.push_back(contactOf(size == 1 ? ContactType::Point : size == 2 ? ContactType::Line : ContactType::Area, n, points, gaps));
    }
    const std::vector<dynamics::ContactPoint> out = pointsOf(contacts);
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(manifoldSizes(out).size(), 1u);
    for (size_t i = 0; i < out.size(); ++i) {
      double deepest = 1.0;
      for (const Contact& c : contacts)
        for (size_t k = 0; k < c.points.size(); ++k)
          if ((c.points[k] - out[i].point).norm() <= 1e-9) deepest = std::min(deepest, c.gapAt(k));
      EXPECT_DOUBLE_EQ(out[i].separation, deepest) << "point " << i << " is not an input point, or not its deepest copy";
      for (size_t j = 0; j < i; ++j) EXPECT_GT((out[i].point - out[j].point).norm(), 1e-9);
    }
    if (out.size() < 3) {  // a point or a segment: every input point on it
      for (const Vector3d& x : all) {
        const Vector3d d = out.back().point - out.front().point;
        const double s = d.squaredNorm() > 0 ? std::clamp((x - out.front().point).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
        EXPECT_LE((out.front().point + s * d - x).norm(), 1e-9);
      }
      continue;
    }
    for (size_t i = 0; i < out.size(); ++i) {  // counter-clockwise about n: every point left of every edge
      const Vector3d& p = out[i].point;
      const Vector3d& q = out[(i + 1) % out.size()].point;
      for (const Vector3d& x : all) EXPECT_GE((q - p).cross(x - p).dot(n), -1e-9 * (q - p).norm());
    }
  }
}

// A contact alone in its plane goes as the detector gave it: its points in their order,
// each with its gap.
TEST(ContactPoints, AContactAloneInItsPlaneKeepsItsPointsAndTheirOrder) {
  const std::vector<Vector3d> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<double> gaps = {-1e-5, 2e-5, -3e-5, 4e-5};
  for (int first = 0; first < 4; ++first) {
    std::vector<Vector3d> points;
    std::vector<double> pointGaps;
    for (int k = 0; k < 4; ++k) points.push_back(square[(first + k) % 4]), pointGaps.push_back(gaps[(first + k) % 4]);
    const std::vector<dynamics::ContactPoint> out = pointsOf({contactOf(ContactType::Area, Vector3d::UnitZ(), points, pointGaps),
                                                             contactOf(ContactType::Point, Vector3d::UnitX(), {{2, 0, 0.5}}, {0})});
    ASSERT_EQ(out.size(), 5u);
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(out[k].point, points[k]);
      EXPECT_EQ(out[k].separation, pointGaps[k]);
    }
  }
}

// The real case: a cup resting on another's rim touches it on the four convex pieces of
// the rim, which the detector reports as four areas sharing their corners (16 points).
// The solver gets one block of the rim's four outer corners.
TEST(ContactPoints, ACupOnACupsRimIsOneBlockOfTheRimsOuterCorners) {
  collision::ObjectDatabase db;
  const auto cup = std::make_shared<collision::PolygonMesh>(test::makeCup(0.5, 0.6, 0.05, 0.05));
  db.add("lower", cup, Eigen::Isometry3d::Identity(), true);
  db.add("upper", cup, Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0.6 - 0.5 * db.tolerance)), false);
  const collision::IntersectionResult r = collision::test4Intersection(db);
  ASSERT_EQ(r.pairs.size(), 1u);
  ASSERT_GT(r.pairs[0].contacts.size(), 1u);  // what the merge is for
  std::vector<dynamics::ContactPoint> out;
  appendContactPoints(r.pairs[0].a, r.pairs[0].b, r.pairs[0].contacts, {0.0, 0.5}, out);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(manifoldSizes(out).size(), 1u);
  for (const dynamics::ContactPoint& p : out) {
    EXPECT_NEAR(std::abs(p.point.x()), 0.5, 1e-9);
    EXPECT_NEAR(std::abs(p.point.y()), 0.5, 1e-9);
    EXPECT_NEAR(p.point.z(), 0.6, db.tolerance);
  }
}

// Two ridges crossing square: a unit box turned 45 degrees about x (its top a ridge along
// x) under one turned 45 degrees about y (its bottom a ridge along y), 0.5 eps into it.
// The detector's point contact between the two edges gets both edges' directions, which
// cross along its normal; the lower box's face contacts with the floor get none.
TEST(ContactPoints, EdgesCrossingGetTheirDirections) {
  collision::ObjectDatabase db;
  const auto box = std::make_shared<collision::PolygonMesh>(collision::makeBox(Vector3d(1, 1, 1)));
  const double half = std::sqrt(0.5);  // the ridge's height over the centre
  const Eigen::Isometry3d lower(Eigen::Translation3d(0, 0, 0) * Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitX()));
  const Eigen::Isometry3d upper(Eigen::Translation3d(0.1, -0.2, 2 * half - 0.5 * db.tolerance) *
                                Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitY()));
  db.add("lower", box, lower, true);
  db.add("upper", box, upper, false);
  const collision::IntersectionResult r = collision::test4Intersection(db);
  ASSERT_EQ(r.pairs.size(), 1u);
  const collision::PairResult& pair = r.pairs[0];
  const auto edgeDirection = [&](bool ofA, int edgeId) -> Vector3d {
    const collision::ObjNode& object = db.objects[ofA ? pair.a : pair.b];
    const collision::MeshEdge& e = object.mesh->edges()[edgeId];
    return (object.X_WO.linear() * (object.mesh->vertices()[e.v1] - object.mesh->vertices()[e.v0])).normalized();
  };
  std::vector<dynamics::ContactPoint> out;
  appendContactPoints(pair.a, pair.b, pair.contacts, {0.0, 0.5}, out, edgeDirection);
  ASSERT_EQ(out.size(), 1u);
  const dynamics::ContactPoint& c = out[0];
  EXPECT_NEAR(c.point.x(), 0.1, 1e-9);
  EXPECT_NEAR(c.point.y(), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(c.edgeA.dot(Vector3d::UnitX())) + std::abs(c.edgeB.dot(Vector3d::UnitX())), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(c.edgeA.dot(Vector3d::UnitY())) + std::abs(c.edgeB.dot(Vector3d::UnitY())), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(c.edgeA.cross(c.edgeB).dot(c.normal)), 1.0, 1e-12);
  // An area between faces names no edges.
  std::vector<dynamics::ContactPoint> faces;
  appendContactPoints(1, 2, {contactOf(ContactType::Area, Vector3d::UnitZ(), {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {0, 0, 0})},
                      {0.0, 0.5}, faces, edgeDirection);
  for (const dynamics::ContactPoint& p : faces) EXPECT_TRUE(p.edgeA.isZero(0.0) && p.edgeB.isZero(0.0));
}

}  // namespace
}  // namespace polysim::sim
