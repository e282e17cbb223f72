#pragma once
// Two paths over a step, each known exactly at any time within it, so that the step loop
// can hand it to collisionDetect() as the body's ctrans:
// - supported (a body with contacts): semi-implicit (symplectic) Euler, gravity into the
//   velocity first, then a straight line at that velocity;
// - free (no contacts): gravity along the way, the exact parabola. Free flight then has
//   no integration error: a dropped body meets the ground at sqrt(2h/g) whatever the step.
// Either way the body turns at constant angular velocity.

#include <Eigen/Geometry>

#include "dynamics/rigid_body.h"

namespace polysim::dynamics {

/// v += g dt for a dynamic body (gravity in m/s^2, dt in s). Angular velocity is kept:
/// the minimal integrator has no gyroscopic term (exact for bodies turning about a
/// principal axis, first order otherwise).
void integrateVelocity(RigidBody& body, const Eigen::Vector3d& gravity, double dt);

/// The pose the body reaches after time s (s in [0, dt]): centre of mass + v s + g s^2 / 2,
/// orientation turned by |w| s about w, where v and w include the push velocities
/// (rigid_body.h). `gravity` is the acceleration along the path: zero
/// for a supported body (its velocity already has it), g for a free one. Static bodies
/// stay put.
Eigen::Isometry3d poseAfter(const RigidBody& body, double s, const Eigen::Vector3d& gravity = Eigen::Vector3d::Zero());

/// Moves the body along that path by time s; a free body's velocity gains gravity * s.
void advancePose(RigidBody& body, double s, const Eigen::Vector3d& gravity = Eigen::Vector3d::Zero());

}  // namespace polysim::dynamics
