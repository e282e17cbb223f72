// solveContacts() sweeps contacts that share no moving body apart: a group that has
// converged stops, while another that converges slowly goes on.

#include <gtest/gtest.h>

#include "dynamics/contact_solver.h"
#include "dynamics/contact_sweeps.h"
#include "dynamics/mass_properties.h"
#include "dynamics/settings.h"

namespace polysim::dynamics {
namespace {

using V3 = Eigen::Vector3d;

RigidBody box(double mass, const V3& size, const V3& position) {
  MassProperties props;
  props.mass = mass;
  props.inertia = mass / 12.0 *
                  V3(size.y() * size.y() + size.z() * size.z(), size.x() * size.x() + size.z() * size.z(),
                     size.x() * size.x() + size.y() * size.y())
                      .asDiagonal();
  RigidBody b = RigidBody::dynamic(props);
  b.position = position;
  b.velocity = V3(0, 0, -9.81 / 60);  // one step of gravity at 60 Hz
  return b;
}

// The four corners under body `a` (centred at x, its bottom face at height z) on body b,
// one block (`manifold` >= 0) or four points on their own (-1).
void addFace(std::vector<ContactPoint>& contacts, int a, int b, double x, double z, int manifold) {
  for (double dx : {-0.5, 0.5})
    for (double dy : {-0.5, 0.5}) contacts.push_back({a, b, V3(x + dx, dy, z), V3::UnitZ(), 0.0, 0.0, 0.5, manifold});
}

// Cube 0 at x = 0 (its corners one block: two sweeps), cube 1 at x = 10 (corner by
// corner: many sweeps), both on the static floor 2; 3 is a plank over both cubes.
std::vector<RigidBody> scene() {
  return {box(1, V3(1, 1, 1), V3(0, 0, 0.5)), box(1, V3(1, 1, 1), V3(10, 0, 0.5)), RigidBody::fixed(),
          box(1, V3(11, 1, 0.2), V3(5, 0, 1.1))};
}

struct Solved {
  std::vector<RigidBody> bodies;
  SolveStats stats;
};

Solved solve(std::vector<ContactPoint> contacts) {
  Solved s{scene(), {}};
  s.stats = solveContacts(s.bodies, contacts, 1.0 / 60);
  return s;
}

TEST(SolveGroups, PilesOnOneFloorAreSweptEachUntilItsOwnConvergence) {
  std::vector<ContactPoint> fast, slow;
  addFace(fast, 0, 2, 0.0, 0.0, 0);
  addFace(slow, 1, 2, 10.0, 0.0, -1);
  const Solved alone0 = solve(fast), alone1 = solve(slow);
  ASSERT_LE(alone0.stats.iterations, 2);
  ASSERT_GT(alone1.stats.iterations, 10);

  std::vector<ContactPoint> both = fast;
  both.insert(both.end(), slow.begin(), slow.end());
  const Solved together = solve(both);
  // The floor, static, links nothing: each cube's sweeps are its own.
  EXPECT_EQ(together.stats.iterations, alone1.stats.iterations);
  EXPECT_EQ(together.stats.rowSolves, alone0.stats.rowSolves + alone1.stats.rowSolves);
  EXPECT_TRUE(together.stats.converged);
  for (int i : {0, 1}) {
    const Solved& alone = i == 0 ? alone0 : alone1;
    EXPECT_EQ(together.bodies[i].velocity, alone.bodies[i].velocity) << "cube " << i;
    EXPECT_EQ(together.bodies[i].angularVelocity, alone.bodies[i].angularVelocity) << "cube " << i;
  }
}

TEST(SolveGroups, AMovingBodyAcrossTwoPilesJoinsThem) {
  std::vector<ContactPoint> contacts;
  addFace(contacts, 0, 2, 0.0, 0.0, 0);
  addFace(contacts, 1, 2, 10.0, 0.0, -1);
  addFace(contacts, 3, 0, 0.0, 1.0, 1);   // the plank on cube 0
  addFace(contacts, 3, 1, 10.0, 1.0, 2);  // and on cube 1
  const Solved joined = solve(contacts);
  EXPECT_EQ(joined.stats.rowSolves, static_cast<long>(contacts.size()) * joined.stats.iterations);
  // Everything comes to rest: the plank is carried by both cubes, the cubes by the floor.
  for (int i : {0, 1, 3}) EXPECT_NEAR(joined.bodies[i].velocity.norm(), 0.0, 1e-9) << "body " << i;
}

// A unit box landing on one corner of its bottom face, the other three a few millimetres
// above the floor (speculative points, each allowed to close by its gap), as one came in
// the tilted pile of 1000 boxes (seed 1, first second). The three held corners ask for a
// turn that sticking friction at them cannot give: the sweeps reach the bodies' final
// velocities in about 50 sweeps and then only pass friction from corner to corner, 1.2e-3
// N s a sweep without end, which would take the solve to the sweep limit and on to shock
// propagation.
TEST(SolveGroups, SweepsStopWhenNoContactPointsVelocityChangesThoughImpulsesDo) {
  MassProperties unitCube;
  unitCube.mass = 1.0;
  unitCube.inertia = Eigen::Matrix3d::Identity() / 6.0;
  RigidBody cube = RigidBody::dynamic(unitCube);
  cube.position = V3(0, 0, 0.5075438140);
  cube.orientation = Eigen::Quaterniond(0.9955693236, -0.0006392704, 0.0064562270, -0.0938063453);
  cube.velocity = V3(-0.6451225104, -0.4159292775, -3.042838488);
  cube.angularVelocity = V3(2.387379015, -3.346032289, 0.09669285595);
  std::vector<RigidBody> bodies{cube, RigidBody::fixed()};
  std::vector<ContactPoint> contacts;
  for (double dx : {0.5, -0.5})
    for (double dy : {0.5, -0.5}) {
      const V3 corner = cube.orientation * V3(dx, dy, -0.5) + cube.position;
      // The point midway between the corner and the floor, its gap the corner's height.
      ContactPoint c{0, 1, V3(corner.x(), corner.y(), corner.z() / 2), V3::UnitZ(), corner.z(), 0.0, 0.5, 0};
      c.normalTurnWithA = 0.0;  // the floor's face: its normal does not turn
      contacts.push_back(c);
    }
  ASSERT_LT(contacts[0].separation, 0.0);  // one corner touches, the others are apart
  ASSERT_GT(contacts[1].separation, 1e-3);
  const double dt = 1.0 / 60, energyBefore = bodies[0].kineticEnergy();
  const SolveStats stats = solveContacts(bodies, contacts, dt, 2.5e-5);
  EXPECT_TRUE(stats.converged);
  EXPECT_LT(stats.iterations, kMaxSolverIterations);
  EXPECT_EQ(stats.shockSweeps, 0);
  EXPECT_LT(bodies[0].kineticEnergy(), energyBefore);
  for (const ContactPoint& c : contacts) {
    // No corner closes by more than its gap over the step, nor the touching one at all.
    EXPECT_GE(bodies[0].velocityAt(c.point).z(), -std::max(c.separation, 0.0) / dt - 1e-9);
    EXPECT_GE(c.normalImpulse, 0.0);
  }
}

// The sweeps' second stop measures what a sweep did to the contact points' velocities:
// a change of spin counts at the body's longest arm, a change of velocity as it is.
TEST(SolveGroups, PointVelocityChangeCountsSpinAtTheLongestArm) {
  RigidBody a = box(1, V3(1, 1, 1), V3::Zero()), b = box(3, V3(2, 1, 1), V3(2, 0, 0));
  const std::vector<solver::BodyReach> bodies{{&a, 0.7}, {&b, 1.2}};
  solver::PointVelocityChange change(bodies);
  change.start();
  EXPECT_EQ(change.largest(), 0.0);
  a.angularVelocity += V3(0, 3e-4, 4e-4);                  // 5e-4 rad/s at 0.7 m
  EXPECT_NEAR(change.largest(), 3.5e-4, 1e-15);
  b.velocity += V3(1e-4, 0, 0), b.angularVelocity += V3(0, 0, 2e-4);  // 1e-4 m/s + 2e-4 rad/s at 1.2 m
  EXPECT_NEAR(change.largest(), 3.5e-4, 1e-15);
  b.angularVelocity += V3(0, 0, 1e-4);
  EXPECT_NEAR(change.largest(), 1e-4 + 3e-4 * 1.2, 1e-15);
  change.start();  // measured from here on
  EXPECT_EQ(change.largest(), 0.0);
}

}  // namespace
}  // namespace polysim::dynamics
