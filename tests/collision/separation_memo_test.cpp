// The separation memo (separation_memo.h): the same value as a fresh measure, from the
// memo only for exactly the same objects, meshes and poses; and from a measure at other
// poses, a lower bound on the signed distance.

#include "collision/separation_memo.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "collision/convex_separation.h"
#include "collision/shapes.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using test::pose;
using V3 = Eigen::Vector3d;

// Random boxes near each other; each pose is measured twice, then moved by one ulp.
TEST(SeparationMemo, GivesTheFreshValueAndReusesOnlyExactlyTheSamePoses) {
  ObjectDatabase db;
  db.add("A", std::make_shared<PolygonMesh>(makeBox(V3(1, 0.5, 0.3))), pose(V3::Zero()), false);
  db.add("B", std::make_shared<PolygonMesh>(makeBox(V3(0.4, 0.8, 0.6))), pose(V3::Zero()), false);
  SeparationMemo memo;
  memo.enable();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(3.0 * u(rng), V3(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    db.objects[1].X_WO = pose(V3(u(rng), u(rng), u(rng)), R);
    const ObjNode& a = db.objects[0];
    const ObjNode& b = db.objects[1];
    const long hitsBefore = memo.hits();
    EXPECT_EQ(memo.measure(a, b), convexSeparation(a, b)) << "trial " << trial;
    EXPECT_EQ(memo.hits(), hitsBefore) << "a new pose is measured";
    EXPECT_EQ(memo.measure(a, b), convexSeparation(a, b)) << "trial " << trial;
    EXPECT_EQ(memo.hits(), hitsBefore + 1) << "the same poses again come from the memo";
    EXPECT_EQ(memo.measure(b, a), convexSeparation(b, a)) << "the other order is its own pair";
    double& x = db.objects[1].X_WO.translation().x();
    x = std::nextafter(x, 2.0);
    const long hitsMoved = memo.hits();
    EXPECT_EQ(memo.measure(a, b), convexSeparation(a, b)) << "trial " << trial;
    EXPECT_EQ(memo.hits(), hitsMoved) << "one ulp of motion is a new pose";
  }
}

// Another mesh under the same id (another database, or a body given a new shape) is
// measured afresh; an object without an id, or a memo not enabled, always is.
TEST(SeparationMemo, AnotherMeshOrNoIdOrNotEnabledIsMeasuredAfresh) {
  ObjectDatabase db;
  db.add("A", std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1))), pose(V3::Zero()), false);
  db.add("B", std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1))), pose(V3(0, 0, 1.25)), false);
  SeparationMemo memo;
  memo.enable();
  ASSERT_NEAR(*memo.measure(db.objects[0], db.objects[1]), 0.25, 1e-12);
  ObjNode taller = db.objects[1];
  taller.mesh = std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 2)));
  EXPECT_NEAR(*memo.measure(db.objects[0], taller), -0.25, 1e-12);
  EXPECT_EQ(memo.hits(), 0);
  ObjNode unnamed = db.objects[1];
  unnamed.id = -1;
  memo.measure(db.objects[0], unnamed);
  memo.measure(db.objects[0], unnamed);
  EXPECT_EQ(memo.hits(), 0);
  SeparationMemo off;
  off.measure(db.objects[0], db.objects[1]);
  EXPECT_NEAR(*off.measure(db.objects[0], db.objects[1]), 0.25, 1e-12);
  EXPECT_EQ(off.hits(), 0);
}

// Distance (m) from world point p to a box of full sizes `size` at pose X: exact.
double distanceToBox(const V3& p, const Eigen::Isometry3d& X, const V3& size) {
  const V3 q = X.inverse() * p;
  return (q.cwiseAbs() - 0.5 * size).cwiseMax(0.0).norm();
}

// Random boxes measured at one pose each, then each moved by a random turn (up to 0.5 rad,
// about a point anywhere near it) and shift: the bound never exceeds the signed distance
// at the new poses. Overlapping, that is the measure itself (minus the depth); apart, at
// most any corner's distance to the other box. Unmoved, the bound is the measure.
TEST(SeparationMemo, LowerBoundNeverExceedsTheSignedDistanceAfterRandomMotions) {
  const V3 sizeA(1, 0.5, 0.3), sizeB(0.4, 0.8, 0.6);
  ObjectDatabase db;
  db.add("A", std::make_shared<PolygonMesh>(makeBox(sizeA)), pose(V3::Zero()), false);
  db.add("B", std::make_shared<PolygonMesh>(makeBox(sizeB)), pose(V3::Zero()), false);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto turn = [&](double most) {
    return Eigen::AngleAxisd(most * u(rng), V3(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  };
  const auto corners = [](const Eigen::Isometry3d& X, const V3& size) {
    std::vector<V3> out;
    for (int k = 0; k < 8; ++k) out.push_back(X * (0.5 * size).cwiseProduct(V3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1)));
    return out;
  };
  int apartKept = 0, overlapping = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    SeparationMemo memo;
    memo.enable();
    ObjNode& a = db.objects[0];
    ObjNode& b = db.objects[1];
    a.X_WO = pose(0.3 * V3(u(rng), u(rng), u(rng)), turn(3.0));
    b.X_WO = pose(V3(u(rng), u(rng), u(rng)), turn(3.0));
    EXPECT_FALSE(memo.lowerBound(a, b)) << "nothing measured yet";
    const std::optional<double> measured = memo.measure(a, b);
    ASSERT_TRUE(measured);
    EXPECT_EQ(memo.lowerBound(a, b), measured) << "unmoved, trial " << trial;
    for (ObjNode* o : {&a, &b}) {  // a turn about a point near the box, then a shift
      const V3 pivot = o->X_WO.translation() + 0.5 * V3(u(rng), u(rng), u(rng));
      const Eigen::Matrix3d R = turn(0.5);
      o->X_WO = pose(R * (o->X_WO.translation() - pivot) + pivot + 0.1 * V3(u(rng), u(rng), u(rng)), R * o->X_WO.linear());
    }
    const std::optional<double> bound = memo.lowerBound(a, b);
    ASSERT_TRUE(bound);
    const double now = *convexSeparation(a, b);
    if (now <= 0.0) {
      ++overlapping;
      EXPECT_LE(*bound, now + 1e-12) << "overlapping, trial " << trial;
      continue;
    }
    double cornerDistance = std::numeric_limits<double>::infinity();
    for (const V3& p : corners(a.X_WO, sizeA)) cornerDistance = std::min(cornerDistance, distanceToBox(p, b.X_WO, sizeB));
    for (const V3& p : corners(b.X_WO, sizeB)) cornerDistance = std::min(cornerDistance, distanceToBox(p, a.X_WO, sizeA));
    EXPECT_LE(*bound, cornerDistance + 1e-12) << "apart, trial " << trial;
    apartKept += *bound > 0.0;
  }
  // Both cases are met often, and the bound is not so loose that it never proves a pair apart.
  EXPECT_GT(overlapping, 200);
  EXPECT_GT(apartKept, 100);
}

// A pair measured in one order is not bounded in the other, nor with another mesh.
TEST(SeparationMemo, LowerBoundOnlyForThePairAndMeshesMeasured) {
  ObjectDatabase db;
  db.add("A", std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1))), pose(V3::Zero()), false);
  db.add("B", std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1))), pose(V3(0, 0, 1.25)), false);
  SeparationMemo memo;
  memo.enable();
  memo.measure(db.objects[0], db.objects[1]);
  db.objects[1].X_WO.translation().z() = 1.5;
  EXPECT_NEAR(*memo.lowerBound(db.objects[0], db.objects[1]), 0.0, 1e-12) << "moved 0.25 away: bound 0.25 less 0.25";
  EXPECT_FALSE(memo.lowerBound(db.objects[1], db.objects[0]));
  ObjNode taller = db.objects[1];
  taller.mesh = std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 2)));
  EXPECT_FALSE(memo.lowerBound(db.objects[0], taller));
}

}  // namespace
}  // namespace polysim::collision
