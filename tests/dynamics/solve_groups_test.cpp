// solveContacts() sweeps contacts that share no moving body apart: a group that has
// converged stops, while another that converges slowly goes on.

#include <gtest/gtest.h>

#include "dynamics/contact_solver.h"
#include "dynamics/mass_properties.h"

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

}  // namespace
}  // namespace polysim::dynamics
