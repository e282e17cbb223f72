// The contact solver's stages beyond its sweeps: the warm start read in world axes, the
// cold restart that keeps a warm start from adding energy, and shock propagation, which
// settles what the sweeps leave when they stop at their limit (contact_solver.h).

#include <gtest/gtest.h>

#include <random>

#include "collision/shapes.h"
#include "dynamics/contact_solver.h"
#include "dynamics/mass_properties.h"
#include "dynamics/settings.h"
#include "tests/test_support.h"

namespace polysim::dynamics {
namespace {

using V3 = Eigen::Vector3d;

// A random vector in the horizontal plane, x drawn before y (test::drawnVector says why).
V3 drawnInPlane(std::uniform_real_distribution<double>& u, std::mt19937& rng) {
  const double x = u(rng);
  return V3(x, u(rng), 0);
}
constexpr double kDt = 1.0 / 60;
constexpr double g = 9.81;

// The ground (body 0) and `count` unit boxes of 1 kg stacked on it, box k centred at
// height k - 0.5, each falling at one step of gravity.
std::vector<RigidBody> stackOfBoxes(int count) {
  const collision::MeshData box = collision::makeBox(V3(1, 1, 1));
  const MassProperties unit = withMass(computeMassProperties(box.vertices, box.faces, 1.0), 1.0);
  std::vector<RigidBody> bodies = {RigidBody::fixed()};
  for (int k = 1; k <= count; ++k) {
    RigidBody& b = bodies.emplace_back(RigidBody::dynamic(unit));
    b.position = V3(0, 0, k - 0.5);
    b.velocity = V3(0, 0, -g * kDt);
  }
  return bodies;
}

// The four corners of each box's bottom face on what is under it, one block per face.
std::vector<ContactPoint> stackContacts(int count, const V3& normal, double mu) {
  std::vector<ContactPoint> contacts;
  for (int k = 1; k <= count; ++k)
    for (double x : {-0.5, 0.5})
      for (double y : {-0.5, 0.5}) contacts.push_back({k, k - 1, V3(x, y, k - 1.0), normal, 0.0, 0.0, mu, k});
  return contacts;
}

double kineticEnergy(const std::vector<RigidBody>& bodies) {
  double e = 0.0;
  for (const RigidBody& b : bodies) e += b.kineticEnergy();
  return e;
}

// A normal tipped 1e-9 rad off z towards azimuth phi: the same plane for the physics,
// but normal.unitOrthogonal() points along (-sin phi, cos phi, 0), any way at all.
V3 tippedUp(double phi) { return V3(1e-9 * std::cos(phi), 1e-9 * std::sin(phi), 1).normalized(); }

// A box on the ground pushed sideways (0.11 m/s), which friction stops within the step,
// then solved again from the same state with one sweep, warm-started from the impulses
// the first solve stored, its normal tipped towards other azimuths. Read as the world
// vector it is, the stored friction stops the box again at once. Read as coordinates in
// the solver's tangent axes, it turned with them (by up to 250 degrees) and pushed the
// box sideways; started cold instead, one sweep's friction is held to nothing by the
// normal impulses not yet found, and the box slides on.
TEST(SolverStages, AWarmStartIsTheSameWhateverTheTangentAxes) {
  const V3 pushed(0.1, 0.05, 0.0);
  std::vector<RigidBody> first = stackOfBoxes(1);
  first[1].velocity += pushed;
  std::vector<ContactPoint> stored = stackContacts(1, tippedUp(0.0), 1.0);
  solveContacts(first, stored, kDt);
  ASSERT_LT(first[1].velocity.norm(), 1e-9);  // it sticks

  for (double phi : {0.0, 1.3, 2.9, 4.4}) {
    std::vector<RigidBody> bodies = stackOfBoxes(1);
    bodies[1].velocity += pushed;
    std::vector<ContactPoint> contacts = stored;
    for (ContactPoint& c : contacts) c.normal = tippedUp(phi);
    solveContacts(bodies, contacts, kDt, 0.0, 1);
    EXPECT_LT(bodies[1].velocity.norm(), 1e-6) << "azimuth " << phi;
  }
}

// Stacks of 2 to 6 boxes moving at random, warm-started with random impulses up to
// 20 N s (a contact that came apart, a box that slid off) and allowed one to three
// sweeps: too few to take the warm start back. The solve must still end with no more
// kinetic energy than it began with.
TEST(SolverStages, AWarmStartTheStepDoesNotNeedAddsNoEnergy) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int restarted = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int count = 2 + trial % 5;
    std::vector<RigidBody> bodies = stackOfBoxes(count);
    for (size_t k = 1; k < bodies.size(); ++k) bodies[k].velocity += test::drawnVector([&] { return u(rng); }), bodies[k].angularVelocity = test::drawnVector([&] { return u(rng); });
    std::vector<ContactPoint> contacts = stackContacts(count, V3::UnitZ(), 0.5 * (1 + u(rng)));
    for (ContactPoint& c : contacts) {
      c.normalImpulse = 10 * (1 + u(rng));
      c.frictionImpulse = 0.5 * c.friction * c.normalImpulse * drawnInPlane(u, rng);
    }
    const double before = kineticEnergy(bodies);
    solveContacts(bodies, contacts, kDt, 0.0, 1 + trial % 3);
    const double after = kineticEnergy(bodies);
    EXPECT_LE(after, before * (1 + 1e-9) + 1e-12) << "trial " << trial;
    restarted += after < 0.5 * before;
  }
  EXPECT_GT(restarted, 100);  // the solves did act
}

// A box lifting off the ground (0.2 to 1 m/s up, drifting sideways at 0.2 to 0.5 m/s,
// so that every corner moves away), warm-started as if it had been sliding there: random
// normal impulses and friction against the drift, too little to stop it (so that the
// warm start alone takes kinetic energy away and the solve is not started cold). A
// contact coming apart pushes nothing and holds nothing: every impulse must end at zero
// and the box keep the velocities it came with. A row holding no impulse at all is
// skipped by the sweeps (contact_sweeps.cpp); one whose normal impulse fell to zero must
// still let go of its friction, or the warm start's would go on slowing the box.
TEST(SolverStages, AContactComingApartLetsGoOfItsWarmStartedFriction) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<RigidBody> bodies = stackOfBoxes(1);
    RigidBody& box = bodies[1];
    const V3 drift = (0.35 + 0.15 * u(rng)) * drawnInPlane(u, rng).normalized();
    box.velocity = drift + V3(0, 0, 0.6 + 0.4 * u(rng));
    const V3 v = box.velocity;
    std::vector<ContactPoint> contacts = stackContacts(1, V3::UnitZ(), 0.5 * (1 + u(rng)));
    for (ContactPoint& c : contacts) {
      c.normalImpulse = 0.5 * (1 + u(rng));
      c.frictionImpulse = -std::min(0.7 * c.friction * c.normalImpulse, drift.norm() / 8) * drift.normalized();
    }
    solveContacts(bodies, contacts, kDt);
    for (const ContactPoint& c : contacts) {
      EXPECT_EQ(c.normalImpulse, 0.0) << "trial " << trial;
      EXPECT_EQ(c.frictionImpulse.norm(), 0.0) << "trial " << trial;
    }
    EXPECT_LT((box.velocity - v).norm(), 1e-12) << "trial " << trial;
    EXPECT_LT(box.angularVelocity.norm(), 1e-12) << "trial " << trial;
  }
}

// A stack of 12 boxes swaying (each box moving and turning at up to 5 cm/s and 0.05
// rad/s, and falling at a step of gravity), its contacts sticking, solved with 20 sweeps.
// Gauss-Seidel carries a correction one level per sweep: it leaves boxes moving at up to
// 0.15 m/s (0.045 m/s after 100 sweeps). Shock propagation settles the stack from the
// ground up, box by box against the one below, to 0.1 mm/s: each level's own sweeps,
// one box on a face's four corners, converge slowly too (friction at the corners tips it).
TEST(SolverStages, ShockPropagationSettlesASwayingStackInTwentySweeps) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const int count = 12;
    std::vector<RigidBody> bodies = stackOfBoxes(count);
    for (size_t k = 1; k < bodies.size(); ++k)
      bodies[k].velocity += 0.05 * drawnInPlane(u, rng), bodies[k].angularVelocity = 0.05 * test::drawnVector([&] { return u(rng); });
    std::vector<ContactPoint> contacts = stackContacts(count, V3::UnitZ(), 0.8);
    const SolveStats stats = solveContacts(bodies, contacts, kDt, 0.0, 20);
    EXPECT_FALSE(stats.converged);
    EXPECT_GT(stats.shockSweeps, 0);
    for (size_t k = 1; k < bodies.size(); ++k) {
      EXPECT_LT(bodies[k].velocity.norm(), 1e-3) << "trial " << trial << ", box " << k;
      EXPECT_LT(bodies[k].angularVelocity.norm(), 1e-3) << "trial " << trial << ", box " << k;
    }
  }
}

// The same swaying stack of 12, its top box also touching a static wall on one side (two
// corners, a horizontal normal, friction). The wall holds nothing up, so the stack is
// still ranked from the ground and settles as before. Ranked by any contact (as when
// `up` is not given), the wall made the top box a first level, the column was ranked
// from both ends, and a middle level held the boxes above it fixed: boxes kept moving at
// up to 10 cm/s, and in the pile of 1000 (seed 11) two ten-box columns by a wall rocked
// for 30 s.
TEST(SolverStages, ShockPropagationRanksByWhatHoldsABodyUpNotByAWallItLeansOn) {
  constexpr int count = 12;
  const int wall = count + 1;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<RigidBody> bodies = stackOfBoxes(count);
    bodies.push_back(RigidBody::fixed());
    for (int k = 1; k <= count; ++k)
      bodies[k].velocity += 0.05 * drawnInPlane(u, rng), bodies[k].angularVelocity = 0.05 * test::drawnVector([&] { return u(rng); });
    std::vector<ContactPoint> contacts = stackContacts(count, V3::UnitZ(), 0.8);
    for (double z : {count - 1.0, count - 0.0})  // the top box's side at x = 0.5 on the wall
      contacts.push_back({count, wall, V3(0.5, 0.0, z), -V3::UnitX(), 0.0, 0.0, 0.8, -1});
    const SolveStats stats = solveContacts(bodies, contacts, kDt, 0.0, 20, V3::UnitZ());
    EXPECT_GT(stats.shockSweeps, 0);
    for (int k = 1; k <= count; ++k) {
      EXPECT_LT(bodies[k].velocity.norm(), 1e-3) << "trial " << trial << ", box " << k;
      EXPECT_LT(bodies[k].angularVelocity.norm(), 1e-3) << "trial " << trial << ", box " << k;
    }
  }
}

// Stacks of 12 swaying, at the default limit. A stack whose contacts all move slower than
// kSettlingSpeed at kMaxSolverIterations is settling and sweeps on, up to the limit; one
// swaying faster (a pile still landing) stops there. A limit below kMaxSolverIterations
// (the scene's `solver_sweeps`) bounds both.
TEST(SolverStages, OnlyASettlingGroupSweepsPastTheMovingLimit) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    for (double sway : {0.2 * kSettlingSpeed, 20 * kSettlingSpeed}) {
      std::vector<RigidBody> bodies = stackOfBoxes(12);
      for (size_t k = 1; k < bodies.size(); ++k)
        bodies[k].velocity += sway * drawnInPlane(u, rng), bodies[k].angularVelocity = sway * test::drawnVector([&] { return u(rng); });
      std::vector<RigidBody> again = bodies;
      std::vector<ContactPoint> contacts = stackContacts(12, V3::UnitZ(), 0.8), same = contacts;
      const SolveStats stats = solveContacts(bodies, contacts, kDt, 0.0, kSettlingSolverSweeps, V3::UnitZ());
      if (sway < kSettlingSpeed) {
        EXPECT_GT(stats.iterations, kMaxSolverIterations) << "trial " << trial;
        EXPECT_LE(stats.iterations, kSettlingSolverSweeps) << "trial " << trial;
      } else {
        EXPECT_EQ(stats.iterations, kMaxSolverIterations) << "trial " << trial;
      }
      EXPECT_EQ(solveContacts(again, same, kDt, 0.0, 20, V3::UnitZ()).iterations, 20) << "trial " << trial;
    }
  }
}

// The same settling stacks, their bodies marked as having rested after their last solve:
// with friction the group is resting, not settling, and stops at kMaxSolverIterations
// (shock propagation holds it); frictionless it sweeps on. A solve marks each body by how
// it leaves: at rest (kRestSpeed) or not.
TEST(SolverStages, ARestingGroupWithFrictionStopsAtTheMovingLimit) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    for (double mu : {0.8, 0.0}) {
      std::vector<RigidBody> bodies = stackOfBoxes(12);
      for (size_t k = 1; k < bodies.size(); ++k) {
        const double sway = 0.2 * kSettlingSpeed;
        bodies[k].velocity += sway * drawnInPlane(u, rng), bodies[k].angularVelocity = sway * test::drawnVector([&] { return u(rng); });
        bodies[k].restedAfterLastSolve = true;
      }
      std::vector<ContactPoint> contacts = stackContacts(12, V3::UnitZ(), mu);
      const SolveStats stats = solveContacts(bodies, contacts, kDt, 0.0, kSettlingSolverSweeps, V3::UnitZ());
      if (mu > 0)
        EXPECT_EQ(stats.iterations, kMaxSolverIterations) << "trial " << trial;
      else
        EXPECT_GT(stats.iterations, kMaxSolverIterations) << "trial " << trial;
      for (size_t k = 1; k < bodies.size(); ++k)
        EXPECT_EQ(bodies[k].restedAfterLastSolve, bodies[k].velocity.norm() < kRestSpeed && bodies[k].angularVelocity.norm() < kRestSpeed);
    }
  }
  std::vector<RigidBody> thrown = stackOfBoxes(2);
  thrown[2].velocity = V3(0, 0, 3);  // leaves the contact: not at rest
  thrown[2].restedAfterLastSolve = true;
  std::vector<ContactPoint> contacts = stackContacts(2, V3::UnitZ(), 0.8);
  solveContacts(thrown, contacts, kDt, 0.0, kSettlingSolverSweeps, V3::UnitZ());
  EXPECT_FALSE(thrown[2].restedAfterLastSolve);
  EXPECT_TRUE(thrown[1].restedAfterLastSolve);
}

// Stacks whose boxes move fast and at random, up as well as down, with 2 sweeps: shock
// propagation hands a level its lower neighbours' velocities without their reaction, so
// a box hit from below can leave with more energy than the stack had. The solver then
// keeps the sweeps' result instead.
TEST(SolverStages, ShockPropagationAddsNoEnergy) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  int shocked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int count = 2 + trial % 5;
    std::vector<RigidBody> bodies = stackOfBoxes(count);
    for (size_t k = 1; k < bodies.size(); ++k) bodies[k].velocity = 2 * test::drawnVector([&] { return u(rng); }), bodies[k].angularVelocity = 2 * test::drawnVector([&] { return u(rng); });
    std::vector<ContactPoint> contacts = stackContacts(count, V3::UnitZ(), 0.5 * (1 + u(rng)));
    const double before = kineticEnergy(bodies);
    const SolveStats stats = solveContacts(bodies, contacts, kDt, 0.0, 2);
    EXPECT_LE(kineticEnergy(bodies), before * (1 + 1e-9) + 1e-12) << "trial " << trial;
    shocked += stats.shockSweeps > 0;
  }
  EXPECT_GT(shocked, 100);
}

// A box thrown up at 2 m/s into two boxes resting on it, one sweep. The sweep shares the
// momentum (1, 0.5 and 0.5 m/s: the thrown box still approaches the one above); shock
// propagation would then hand each level the velocity of the one below without its
// reaction (all three at 1 m/s: 3 kg m/s from 2, 1.5 J from 0.75). That result raises
// kinetic energy over the sweeps' and is not kept: the boxes keep the momentum they had,
// the ground pulling nothing.
TEST(SolverStages, ShockPropagationKeepsNoResultThatAddsEnergy) {
  std::vector<RigidBody> bodies = stackOfBoxes(3);
  for (RigidBody& b : bodies) b.velocity.setZero();
  bodies[1].velocity = V3(0, 0, 2);
  std::vector<ContactPoint> contacts = stackContacts(3, V3::UnitZ(), 0.5);
  const SolveStats stats = solveContacts(bodies, contacts, kDt, 0.0, 1);
  ASSERT_GT(stats.shockSweeps, 0);
  double momentum = 0.0;
  for (const RigidBody& b : bodies) momentum += b.isStatic ? 0.0 : b.velocity.z() / b.inverseMass;
  EXPECT_NEAR(momentum, 2.0, 1e-9);
  // Nor does the sweep started again from that pass's impulses end above the sweeps' own
  // 0.75 J (1, 0.5 and 0.5 m/s): whatever is kept, it is no more than that.
  EXPECT_LE(kineticEnergy(bodies), 0.75 * (1 + 1e-9));
}

// Pushes (split impulses) part an overlap deeper than the allowed one by what is beyond it,
// over the step, and the pushed box's support holds: the box under an overlapping one is
// not pushed into the floor, and a box elsewhere is not pushed at all.
TEST(SolverStages, PushesPartADeepOverlapAndTheFloorHoldsWhatIsUnderIt) {
  std::vector<RigidBody> bodies = stackOfBoxes(2);
  std::vector<ContactPoint> contacts = stackContacts(2, V3::UnitZ(), 0.5);
  const collision::MeshData box = collision::makeBox(V3(1, 1, 1));
  RigidBody& aside = bodies.emplace_back(RigidBody::dynamic(withMass(computeMassProperties(box.vertices, box.faces, 1.0), 1.0)));
  aside.position = V3(5, 0, 0.5);
  for (double x : {-0.5, 0.5})
    for (double y : {-0.5, 0.5}) contacts.push_back({3, 0, V3(5 + x, y, 0.0), V3::UnitZ(), -1e-5, 0.0, 0.5, 3});
  const double overlap = 3e-3, allowed = 2.5e-5;
  for (ContactPoint& c : contacts)
    if (c.a == 2) c.separation = -overlap;
  solveContacts(bodies, contacts, kDt, allowed);
  const auto pushAt = [&bodies](int i, const V3& p) -> V3 {
    const RigidBody& b = bodies[i];
    return b.pushVelocity + b.pushAngularVelocity.cross(p - b.centerOfMass());
  };
  for (const ContactPoint& c : contacts) {
    const double apart = (pushAt(c.a, c.point) - (c.b == 0 ? V3::Zero() : pushAt(c.b, c.point))).dot(c.normal);
    if (c.a == 2) EXPECT_NEAR(apart, (overlap - allowed) / kDt, 1e-8);  // parted by what is beyond the allowed depth
    else EXPECT_NEAR(apart, 0.0, 1e-8) << "body " << c.a;               // held by the floor; the box aside untouched
  }
  EXPECT_EQ(bodies[3].pushVelocity, V3::Zero());
}

}  // namespace
}  // namespace polysim::dynamics
