// The separation memo (separation_memo.h): the same value as a fresh measure, from the
// memo only for exactly the same objects, meshes and poses.

#include "collision/separation_memo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

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

}  // namespace
}  // namespace polysim::collision
