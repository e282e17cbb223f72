// The sleep rule for one body (dynamics/sleep.h): slow time accumulates while the body's
// centre and the farthest point of its spin stay under the speed, and starts over as soon
// as either does not.

#include "dynamics/sleep.h"

#include <gtest/gtest.h>

namespace polysim::dynamics {
namespace {

constexpr double kDt = 1.0 / 60;

RigidBody unitBox() { return RigidBody::dynamic({1.0, 1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() / 6}); }

TEST(SleepRule, SlowTimeAddsUpAndStartsOverWhenTheBodySpeedsUp) {
  const SleepSettings rule;
  RigidBody b = unitBox();
  b.velocity = Eigen::Vector3d(0.5 * rule.speed, 0, 0);
  double slow = 0.0;
  for (int k = 0; k < 20; ++k) slow = slowTimeAfterStep(b, 0.87, kDt, slow, rule);
  EXPECT_NEAR(slow, 20 * kDt, 1e-12);
  b.velocity.x() = 2 * rule.speed;
  slow = slowTimeAfterStep(b, 0.87, kDt, slow, rule);
  EXPECT_EQ(slow, 0.0);  // not 20 steps' worth kept
  b.velocity.x() = 0.5 * rule.speed;
  EXPECT_NEAR(slowTimeAfterStep(b, 0.87, kDt, slow, rule), kDt, 1e-15);
}

TEST(SleepRule, SpinCountsAtTheFarthestPoint) {
  const SleepSettings rule;
  RigidBody b = unitBox();
  const double size = 0.87;                                        // m
  b.angularVelocity = Eigen::Vector3d(0, 0, 1.1 * rule.speed / size);  // its corner moves at 1.1 x speed
  EXPECT_EQ(slowTimeAfterStep(b, size, kDt, 0.3, rule), 0.0);
  b.angularVelocity.z() = 0.9 * rule.speed / size;
  EXPECT_NEAR(slowTimeAfterStep(b, size, kDt, 0.3, rule), 0.3 + kDt, 1e-15);
}

TEST(SleepRule, AStaticBodyIsAlwaysSlow) {
  RigidBody ground = RigidBody::fixed();
  EXPECT_NEAR(slowTimeAfterStep(ground, 10.0, kDt, 1.0, SleepSettings{}), 1.0 + kDt, 1e-15);
}

}  // namespace
}  // namespace polysim::dynamics
