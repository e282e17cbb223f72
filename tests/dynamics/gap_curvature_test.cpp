// The solver's targets see where turning bodies take a contact's gap within the step: a
// point on a face that turns towards it closes quadratically, which a velocity target
// alone (-gap / dt) misses. Checked against the exact gap after the step, from the
// bodies' exact poses.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "collision/shapes.h"
#include "dynamics/contact_solver.h"
#include "dynamics/integrator.h"
#include "tests/test_support.h"

namespace polysim::dynamics {
namespace {

using V3 = Eigen::Vector3d;

RigidBody unitBox(double mass) {
  const collision::MeshData box = collision::makeBox(V3(1, 1, 1));
  return RigidBody::dynamic(withMass(computeMassProperties(box.vertices, box.faces, 1.0), mass));
}

// Body 1 (a heavy unit box, centre 0.5 m below the origin) turns at 2 rad/s about y; its
// top face touches body 0's point at the origin, which is at rest. The face's normal is
// (sin 2t, 0, cos 2t) and the gap of the fixed point is -(1 - cos 2t) / 2 = -t^2 to second
// order: 0.28 mm, nearly three tolerances, in a step of 1/60 s, while the relative normal
// velocity is 0 now. The solve must leave the point at a gap >= 0 at the step's end, to
// third order in dt, without pushing it off by more than that.
TEST(GapCurvature, APointOnAFaceTurningTowardsItEndsTheStepOnTheFace) {
  const double dt = 1.0 / 60, spin = 2.0;
  std::vector<RigidBody> bodies = {unitBox(1.0), unitBox(1000.0)};
  bodies[0].position = V3(0, 0, 0.5);
  bodies[1].position = V3(0, 0, -0.5);
  bodies[1].angularVelocity = V3(0, spin, 0);
  const V3 p = V3::Zero();
  std::vector<ContactPoint> contacts = {{0, 1, p, V3::UnitZ(), 0.0, 0.0, 0.5, -1, 0.0}};  // the face is body 1's
  const Eigen::Isometry3d a0 = poseAfter(bodies[0], 0.0), b0 = poseAfter(bodies[1], 0.0);
  solveContacts(bodies, contacts, dt);

  const Eigen::Isometry3d a1 = poseAfter(bodies[0], dt), b1 = poseAfter(bodies[1], dt);
  const V3 normal = b1.linear() * V3::UnitZ();
  const double gap = normal.dot(a1 * (a0.inverse() * p) - b1 * (b0.inverse() * p));
  const double uncorrected = -(1 - std::cos(spin * dt)) / 2;  // m: what a target of 0 leaves
  EXPECT_LT(uncorrected, -2.7e-4);
  EXPECT_GT(gap, -std::pow(spin * dt, 3));  // third-order rest, 3.7e-5 m here
  EXPECT_LT(gap, std::pow(spin * dt, 3));
}

// The point sliding the other way, +x at 1 m/s relative to the face, over a face that
// turns away beneath it: the gap opens (the curvature is positive), the target stays 0
// and nothing is pushed.
TEST(GapCurvature, AFaceTurningAwayAddsNothing) {
  std::vector<RigidBody> bodies = {unitBox(1.0), unitBox(1000.0)};
  bodies[0].position = V3(0, 0, 0.5);
  bodies[1].position = V3(0, 0, -0.5);
  bodies[0].velocity = V3(2.0, 0, 0);  // the face's point under it moves at 1 m/s
  bodies[1].angularVelocity = V3(0, 2.0, 0);
  std::vector<ContactPoint> contacts = {{0, 1, V3::Zero(), V3::UnitZ(), 0.0, 0.0, 0.0, -1, 0.0}};
  solveContacts(bodies, contacts, 1.0 / 60);
  EXPECT_EQ(contacts[0].normalImpulse, 0.0);
}

// The gap of two lines moving with their bodies: along their common normal (oriented as
// `towardsA`), from b's line to a's. Lines, not segments: the crossing stays inside both.
double lineGap(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const V3& pointA, const V3& pointB, const V3& edgeA,
               const V3& edgeB, const V3& towardsA) {
  V3 n = (a.linear() * edgeA).cross(b.linear() * edgeB).normalized();
  if (n.dot(towardsA) < 0) n = -n;
  return n.dot(a * pointA - b * pointB);
}

// Two edges crossing at a point, their bodies turning and sliding at random: the normal
// (the edges' cross product) turns with both, and the points closest on the two edges
// slide along them. Both bodies' spins and slides make the gap curve; where it curves
// closed, the solve must leave the edges crossing at a gap within third order of 0 at the
// step's end, not pushed off further; where it opens, nothing pushes. Body 1 turning about
// body 0's edge at 2 rad/s, edges crossing square: the gap closes by (1 - cos 2t) / 2, as
// the face's does above, yet a normal turning with the mean of the two spins saw none of it.
TEST(GapCurvature, CrossingEdgesEndTheStepCrossing) {
  const double dt = 1.0 / 240;
  // m: third order in dt, for spins up to 5 rad/s and speeds up to 1.7 m/s; the free
  // motion closes the gap by up to 3,500 dt^3 here.
  const double bound = 300 * std::pow(dt, 3);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  auto random = [&](double size) -> V3 { return size * test::drawnVector([&] { return uniform(rng); }); };
  int closing = 0;
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const V3 edgeA = trial == 0 ? V3::UnitX() : random(1.0).normalized();
    V3 edgeB = trial == 0 ? V3::UnitY() : random(1.0).normalized();
    if (std::abs(edgeA.dot(edgeB)) > 0.9) continue;  // nearly parallel edges make a line, not a crossing
    const V3 n = edgeA.cross(edgeB).normalized();       // from b towards a
    std::vector<RigidBody> bodies = {unitBox(1.0), unitBox(1000.0)};
    bodies[0].position = 0.5 * n + random(0.3);
    bodies[1].position = -0.5 * n + random(0.3);
    if (trial == 0) {
      bodies[0].position = V3(0, 0, 0.5), bodies[1].position = V3(0, 0, -0.5), bodies[1].angularVelocity = V3(2, 0, 0);
    } else {
      bodies[0].angularVelocity = random(3.0), bodies[1].angularVelocity = random(3.0);
      bodies[0].velocity = random(1.0), bodies[1].velocity = random(1.0);
    }
    const V3 p = V3::Zero();  // the crossing, at a gap of 0, approaching at 0 now
    bodies[0].velocity -= n.dot(bodies[0].velocityAt(p) - bodies[1].velocityAt(p)) * n;
    // With friction, as in the face's test: the sliding it slows pays for the push.
    ContactPoint c{0, 1, p, n, 0.0, 0.0, 0.5, -1, 0.5};
    c.edgeA = edgeA, c.edgeB = edgeB;
    std::vector<ContactPoint> contacts = {c};
    const Eigen::Isometry3d a0 = poseAfter(bodies[0], 0.0), b0 = poseAfter(bodies[1], 0.0);
    const V3 inA = a0.inverse() * p, inB = b0.inverse() * p, edgeInA = a0.linear().transpose() * edgeA,
             edgeInB = b0.linear().transpose() * edgeB;
    const double free = lineGap(poseAfter(bodies[0], dt), poseAfter(bodies[1], dt), inA, inB, edgeInA, edgeInB, n);
    solveContacts(bodies, contacts, dt);
    const double gap = lineGap(poseAfter(bodies[0], dt), poseAfter(bodies[1], dt), inA, inB, edgeInA, edgeInB, n);
    if (trial == 0) {
      EXPECT_NEAR(free, -(1 - std::cos(2 * dt)) / 2, 1e-12);
    }
    // Never left crossing deeper than third order, never pushed off further than that
    // past where the free motion would take it.
    EXPECT_GT(gap, -bound) << "closing by " << free;
    EXPECT_LT(gap, std::max(free, 0.0) + bound) << "closing by " << free;
    closing += free < -bound;
  }
  EXPECT_GT(closing, 50);  // the correction is exercised
}

}  // namespace
}  // namespace polysim::dynamics
