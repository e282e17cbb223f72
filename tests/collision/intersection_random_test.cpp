// Differential test: test4Intersection() (broad steps + polygon tests + reduction) against
// a brute-force reference that tests every polygon pair, on random poses. The fraction
// of interpenetrating cases is asserted to lie in a band, so both outcomes are exercised.

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "collision/contact_reduction.h"
#include "collision/intersection.h"
#include "collision/shapes.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;

PairResult bruteForce(const ObjectDatabase& db, bool withGeometry = false) {
  PairResult r;
  std::vector<WorldFaces> faces(2);
  faces[0].reset(db.objects[0]);
  faces[1].reset(db.objects[1]);
  const int na = db.objects[0].mesh->faceCount(), nb = db.objects[1].mesh->faceCount();
  for (int f = 0; f < na; ++f) faces[0].box(f);
  for (int f = 0; f < nb; ++f) faces[1].box(f);
  PolygonScratch scratch;
  std::vector<Contact> raw;
  for (int fa = 0; fa < na; ++fa)
    for (int fb = 0; fb < nb; ++fb) {
      const PolygonPairOutcome o = testPolygonPair(faces[0].view(fa), faces[1].view(fb), db.tolerance, &raw, scratch);
      r.status = std::max(r.status, o.status);
    }
  const ObjNode &A = db.objects[0], &B = db.objects[1];
  const PairGeometry geometry{A.mesh.get(), B.mesh.get(), A.X_WO.linear(), B.X_WO.linear()};
  if (r.status == Status::Contact) r.contacts = reduceContacts(raw, db.tolerance, withGeometry ? &geometry : nullptr);
  return r;
}

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

TEST(IntersectionRandom, BroadStepsLoseNothingAgainstAllPolygonPairs) {
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<double> distance(0.6, 1.5);
  const std::vector<std::shared_ptr<PolygonMesh>> shapes = {
      std::make_shared<PolygonMesh>(makeBox(V3(1, 0.6, 0.8))), std::make_shared<PolygonMesh>(makeIcosphere(0.6, 1)),
      std::make_shared<PolygonMesh>(test::makeStaple())};
  int interpenetrating = 0, contact = 0;
  const int trials = 600;
  for (int trial = 0; trial < trials; ++trial) {
    ObjectDatabase db;
    const auto& meshA = shapes[trial % 3];
    const auto& meshB = shapes[(trial / 3) % 3];
    const V3 direction = V3::Random().normalized();
    const double scale = 0.5 * (meshA->bounds().sizes().norm() + meshB->bounds().sizes().norm()) / 2;
    db.add("A", meshA, test::pose(V3::Zero(), randomRotation(rng)), false);
    db.add("B", meshB, test::pose(distance(rng) * scale * direction, randomRotation(rng)), false);
    const IntersectionResult fast = test4Intersection(db);
    const PairResult slow = bruteForce(db);
    ASSERT_EQ(toString(fast.status), toString(slow.status)) << "trial " << trial;
    if (slow.status == Status::Contact) {
      ++contact;
      EXPECT_EQ(fast.pairs[0].contacts.size(), slow.contacts.size()) << "trial " << trial;
    }
    interpenetrating += slow.status == Status::Interpenetrating;
  }
  const double fraction = static_cast<double>(interpenetrating) / trials;
  EXPECT_GT(fraction, 0.25);
  EXPECT_LT(fraction, 0.75);
  RecordProperty("interpenetrating_fraction", std::to_string(fraction));
  RecordProperty("contact_cases", contact);
}

// Summed sizes of a pair's contacts by type: count, then total area, length, points.
struct ContactSums {
  int areas = 0, lines = 0, points = 0;
  double area = 0, length = 0;
};
ContactSums sums(const std::vector<Contact>& contacts) {
  ContactSums s;
  for (const Contact& c : contacts) {
    if (c.type == ContactType::Area) {
      ++s.areas;
      for (size_t i = 1; i + 1 < c.points.size(); ++i)
        s.area += 0.5 * (c.points[i] - c.points[0]).cross(c.points[i + 1] - c.points[0]).norm();
    }
    if (c.type == ContactType::Line) ++s.lines, s.length += (c.points[1] - c.points[0]).norm();
    if (c.type == ContactType::Point) ++s.points;
  }
  return s;
}

// Boxes resting on a triangulated floor and on a larger box, at random places, turns
// and tilts (flat: an area; about an edge: a line; corner down: a point), some hanging
// over the lower box's edge. Finding the areas first lets the side faces skip gathering
// (area_cover.h); the contacts must be those of every polygon pair reduced together.
TEST(IntersectionRandom, RestingBoxesGiveTheContactsOfAllPolygonPairs) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto floor = std::make_shared<PolygonMesh>(makeTriangulatedFloor(6, 6, 7));
  const auto block = std::make_shared<PolygonMesh>(makeBox(V3(2, 2, 1)));
  int areas = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const V3 size(0.6 + 0.3 * u(rng), 0.6 + 0.3 * u(rng), 0.5 + 0.2 * u(rng));
    const auto box = std::make_shared<PolygonMesh>(makeBox(size));
    const Eigen::Matrix3d yaw = Eigen::AngleAxisd(M_PI * u(rng), V3::UnitZ()).toRotationMatrix();
    const int tilt = trial % 3;  // 0 flat, 1 on an edge, 2 on a corner
    Eigen::Matrix3d R = yaw;
    if (tilt >= 1) R = R * Eigen::AngleAxisd(0.3, V3::UnitX()).toRotationMatrix();
    if (tilt == 2) R = R * Eigen::AngleAxisd(0.4, V3::UnitY()).toRotationMatrix();
    // Lift the box so that its lowest vertex rests a quarter tolerance into the surface.
    double lowest = 1e300;
    for (const V3& v : box->vertices()) lowest = std::min(lowest, (R * v).z());
    const bool onBlock = trial % 2 == 1;
    const double top = onBlock ? 0.5 : 0.0;
    const double reach = onBlock ? 1.2 : 2.5;  // the block's half width plus some overhang
    ObjectDatabase db;
    db.add("box", box, test::pose(V3(reach * u(rng), reach * u(rng), top - lowest - 0.25 * db.tolerance), R), false);
    if (onBlock) db.add("block", block, test::pose(V3::Zero()), true);
    else db.add("floor", floor, test::pose(V3::Zero()), true);
    const IntersectionResult fast = test4Intersection(db);
    const PairResult slow = bruteForce(db, true);
    ASSERT_EQ(toString(fast.status), toString(slow.status)) << "trial " << trial;
    if (slow.status != Status::Contact) continue;
    const ContactSums f = sums(fast.pairs[0].contacts), b = sums(slow.contacts);
    EXPECT_EQ(f.areas, b.areas) << "trial " << trial;
    EXPECT_EQ(f.lines, b.lines) << "trial " << trial;
    EXPECT_EQ(f.points, b.points) << "trial " << trial;
    EXPECT_NEAR(f.area, b.area, 1e-9) << "trial " << trial;
    EXPECT_NEAR(f.length, b.length, 1e-9) << "trial " << trial;
    areas += f.areas > 0;
  }
  EXPECT_GT(areas, 60);  // the flat cases that land on something are areas
}

}  // namespace
}  // namespace polysim::collision
