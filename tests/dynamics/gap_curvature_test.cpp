// The solver's targets see where turning bodies take a contact's gap within the step: a
// point on a face that turns towards it closes quadratically, which a velocity target
// alone (-gap / dt) misses. Checked against the exact gap after the step, from the
// bodies' exact poses.

#include <gtest/gtest.h>

#include "collision/shapes.h"
#include "dynamics/contact_solver.h"
#include "dynamics/integrator.h"

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

}  // namespace
}  // namespace polysim::dynamics
