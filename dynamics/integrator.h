#pragma once
// Semi-implicit (symplectic) Euler: velocities first (gravity), then positions with the
// new velocities. Over a step the centre of mass moves in a straight line and the body
// turns at constant angular velocity, so the pose at any fraction of a step is known
// exactly; the step loop hands that path to collisionDetect() as the body's ctrans.

#include <Eigen/Geometry>

#include "dynamics/rigid_body.h"

namespace polysim::dynamics {

/// v += g dt for a dynamic body (gravity in m/s^2, dt in s). Angular velocity is kept:
/// the minimal integrator has no gyroscopic term (exact for bodies turning about a
/// principal axis, first order otherwise).
void integrateVelocity(RigidBody& body, const Eigen::Vector3d& gravity, double dt);

/// The pose the body reaches after time s (s in [0, dt]) at its current velocities:
/// centre of mass + v s, orientation turned by |w| s about w. Static bodies stay put.
Eigen::Isometry3d poseAfter(const RigidBody& body, double s);

/// Moves the body along that path by time s.
void advancePose(RigidBody& body, double s);

}  // namespace polysim::dynamics
