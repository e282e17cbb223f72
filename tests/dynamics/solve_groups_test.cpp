// solveContacts() sweeps contacts that share no moving body apart: a group that has
// converged stops, while another that converges slowly goes on; a solve of many groups
// sweeps them on two threads, with the impulses each group gets alone.

#include <gtest/gtest.h>

#include <random>

#include "dynamics/contact_solver.h"
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

// Columns of two cubes on the static floor (the last body), each column a group: cube 2k
// on the floor at x = 3k, cube 2k + 1 on it, of seeded masses, landing at seeded speeds,
// each face's corners one block or four points on their own, friction drawn per column.
// Straight down: any sliding leaves the point-by-point columns unconverged at the sweep
// limit, and shock propagation and the energy check then act on the whole solve.
struct Columns {
  std::vector<RigidBody> bodies;
  std::vector<std::vector<ContactPoint>> contacts;  // per column, indexing `bodies`
};

Columns columns(int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Columns c;
  for (int k = 0; k < count; ++k) {
    for (int level : {0, 1}) {
      RigidBody b = box(1.0 + 0.5 * (unit(random) + 1.0), V3(1, 1, 1), V3(3.0 * k, 0, 0.5 + level));
      b.velocity = V3(0, 0, -0.5 - 0.5 * (unit(random) + 1.0));
      c.bodies.push_back(b);
    }
    const double friction = 0.3 + 0.2 * unit(random);
    std::vector<ContactPoint>& mine = c.contacts.emplace_back();
    addFace(mine, 2 * k, 2 * count, 3.0 * k, 0.0, random() % 2 ? 2 * k : -1);
    addFace(mine, 2 * k + 1, 2 * k, 3.0 * k, 1.0, random() % 2 ? 2 * k + 1 : -1);
    for (ContactPoint& p : mine) p.friction = friction;
  }
  c.bodies.push_back(RigidBody::fixed());
  return c;
}

TEST(SolveGroups, ManyGroupsSweptOnTwoThreadsGetWhatEachGetsAlone) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    const int count = 12;
    const Columns made = columns(count, seed);
    std::vector<ContactPoint> all;
    for (const std::vector<ContactPoint>& column : made.contacts) all.insert(all.end(), column.begin(), column.end());
    ASSERT_GE(static_cast<int>(all.size()), kSharedSweepRows);  // shared between two threads
    std::vector<RigidBody> together = made.bodies;
    const SolveStats stats = solveContacts(together, all, 1.0 / 60);
    ASSERT_TRUE(stats.converged) << "seed " << seed << ": no stage after the sweeps acts on every group";

    long rowSolves = 0;
    int iterations = 0;
    for (int k = 0; k < count; ++k) {
      ASSERT_LT(static_cast<int>(made.contacts[k].size()), kSharedSweepRows);  // one thread
      std::vector<RigidBody> alone = made.bodies;
      std::vector<ContactPoint> mine = made.contacts[k];
      const SolveStats own = solveContacts(alone, mine, 1.0 / 60);
      rowSolves += own.rowSolves;
      iterations = std::max(iterations, own.iterations);
      for (int i : {2 * k, 2 * k + 1}) {
        EXPECT_EQ(together[i].velocity, alone[i].velocity) << "seed " << seed << ", cube " << i;
        EXPECT_EQ(together[i].angularVelocity, alone[i].angularVelocity) << "seed " << seed << ", cube " << i;
      }
    }
    EXPECT_EQ(stats.rowSolves, rowSolves) << "seed " << seed;
    EXPECT_EQ(stats.iterations, iterations) << "seed " << seed;
    EXPECT_GT(iterations, 2) << "seed " << seed << ": the columns take some sweeps";
  }
}

}  // namespace
}  // namespace polysim::dynamics
