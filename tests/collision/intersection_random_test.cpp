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

PairResult bruteForce(const ObjectDatabase& db) {
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
  if (r.status == Status::Contact) r.contacts = reduceContacts(raw, db.tolerance);
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

}  // namespace
}  // namespace polysim::collision
