// Warm starting a step's solve from the last one (sim/warm_start.h): which old point a
// new one starts from, whichever way round its pair comes.

#include "sim/warm_start.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <memory>

#include "collision/shapes.h"
#include "sim/contact_points.h"
#include "sim/speculative_contacts.h"
#include "tests/sim/scenario_support.h"

namespace polysim::sim {
namespace {

using dynamics::ContactPoint;
using test::V3;

ContactPoint pointOf(int a, int b, const Eigen::Vector3d& at, const Eigen::Vector3d& normal) {
  ContactPoint p;
  p.a = a, p.b = b, p.point = at, p.normal = normal;
  return p;
}

// Last step's point: box 2 resting on box 1 (normal from 1 towards 2), pressed with 5 N
// and held sideways with 1 N along x.
std::vector<ContactPoint> lastStep() {
  ContactPoint old = pointOf(2, 1, V3(0.5, 0.5, 1.0), V3(0, 0, 1));
  old.normalImpulse = 5.0, old.frictionImpulse = V3(1.0, 0, 0);
  return {old};
}

constexpr double kHorizon = 0.01;  // s

TEST(WarmStart, APointOfTheSamePairAtTheSamePlaceStartsFromItsForce) {
  std::vector<ContactPoint> points{pointOf(2, 1, V3(0.5, 0.5, 1.0) + V3(0, 0, 0.5e-3), V3(0, 0, 1))};
  warmStartFromLastSolve(lastStep(), points, kHorizon);
  EXPECT_DOUBLE_EQ(points[0].normalImpulse, 5.0 * kHorizon);
  EXPECT_TRUE(points[0].frictionImpulse.isApprox(V3(1.0, 0, 0) * kHorizon));
}

// The same contact, its pair the other way round: its normal points from 2 towards 1,
// and the friction on its `a` (box 1) is the opposite of box 2's.
TEST(WarmStart, APairTheOtherWayRoundStartsFromTheSameForceOnEachBody) {
  std::vector<ContactPoint> points{pointOf(1, 2, V3(0.5, 0.5, 1.0), V3(0, 0, -1))};
  warmStartFromLastSolve(lastStep(), points, kHorizon);
  EXPECT_DOUBLE_EQ(points[0].normalImpulse, 5.0 * kHorizon);
  EXPECT_TRUE(points[0].frictionImpulse.isApprox(V3(-1.0, 0, 0) * kHorizon));
}

TEST(WarmStart, AnotherPlaceAnotherPairOrAnOppositeNormalStartsFromNothing) {
  std::vector<ContactPoint> points{
      pointOf(2, 1, V3(0.5, 0.5, 1.0) + V3(kWarmStartRadius * 1.5, 0, 0), V3(0, 0, 1)),  // too far
      pointOf(2, 0, V3(0.5, 0.5, 1.0), V3(0, 0, 1)),                                    // another pair
      pointOf(2, 1, V3(0.5, 0.5, 1.0), V3(0, 0, -1)),                                   // facing the other way
      pointOf(1, 2, V3(0.5, 0.5, 1.0), V3(0, 0, 1)),                                    // so, the other way round
  };
  warmStartFromLastSolve(lastStep(), points, kHorizon);
  for (const ContactPoint& p : points) {
    EXPECT_EQ(p.normalImpulse, 0.0);
    EXPECT_TRUE(p.frictionImpulse.isZero(0.0));
  }
}

// Where the order changes in a run: the solver's contacts of a box resting on another
// come out with the moving body first, so one still at a step's start and moving at the
// next swaps the pair. Every point still starts from last step's force.
TEST(WarmStart, ContactsOfABodyStillAtOneStepAndMovingAtTheNextKeepTheirForces) {
  collision::ObjectDatabase db;
  const auto box = std::make_shared<collision::PolygonMesh>(collision::makeBox(V3(1, 1, 1)));
  db.add("lower", box, Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0)), false);
  db.add("upper", box, Eigen::Isometry3d(Eigen::Translation3d(0.2, 0.1, 1.0 - 1e-5)), false);
  const auto everyPair = [](const collision::PairResult&) { return true; };
  const auto stillFirst = [](int k) { return k == 0 ? SpeculativeRole::Still : SpeculativeRole::Moving; };
  const auto stillSecond = [](int k) { return k == 1 ? SpeculativeRole::Still : SpeculativeRole::Moving; };
  collision::IntersectionWorkspace ws;
  const auto pointsWith = [&](const auto& roleOf) {
    const std::vector<collision::PairResult> pairs = withSpeculativeContacts(db, ws, kSpeculativeReach, {}, {}, roleOf, everyPair);
    std::vector<ContactPoint> points;
    for (const collision::PairResult& p : pairs) appendContactPoints(p.a, p.b, p.contacts, {0.0, 0.5}, points);
    return points;
  };
  std::vector<ContactPoint> last = pointsWith(stillFirst);
  ASSERT_EQ(last.size(), 4u);
  for (ContactPoint& p : last) p.normalImpulse = 2.0, p.frictionImpulse = p.a == 1 ? V3(0.3, 0, 0) : V3(-0.3, 0, 0);
  std::vector<ContactPoint> next = pointsWith(stillSecond);
  ASSERT_EQ(next.size(), 4u);
  ASSERT_NE(next[0].a, last[0].a);  // the pair came the other way round
  warmStartFromLastSolve(last, next, kHorizon);
  for (const ContactPoint& p : next) {
    EXPECT_DOUBLE_EQ(p.normalImpulse, 2.0 * kHorizon);
    EXPECT_TRUE(p.frictionImpulse.isApprox((p.a == 1 ? V3(0.3, 0, 0) : V3(-0.3, 0, 0)) * kHorizon));  // on the upper box: +x
  }
}

}  // namespace
}  // namespace polysim::sim
