#pragma once
// The bridge from dynamics to collision: a body's path over a sub-step as the seed's
// ctrans update function (contacts go the other way in contact_points.h).

#include <Eigen/Geometry>

#include "dynamics/rigid_body.h"

namespace polysim::sim {

/// What ctrans needs to place a body at a fraction of a sub-step.
struct BodyPath {
  const dynamics::RigidBody* body = nullptr;
  double duration = 0.0;                              // s: the sub-step [0, 1] stands for
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // m/s^2 along the path: g when free, 0 when supported
};

/// ctrans: the pose the integrator reaches after s * duration (dynamics::poseAfter).
void bodyPathPose(double s, const void* info, Eigen::Isometry3d& X_WO);

/// How far any vertex can move along the path (m): |v| T + |g| T^2 / 2 + |w| T r, where
/// `radius` is the body's farthest vertex from its centre of mass and v, w include the
/// push velocities.
double pathMotionBound(const dynamics::RigidBody& body, double radius, double duration,
                       const Eigen::Vector3d& gravity = Eigen::Vector3d::Zero());

/// How fast any vertex can move along the path, in m per unit of the path's parameter s
/// in [0, 1] (ObjNode::motionRate): T (|v| + |g| T + |w| r), the speed at the path's
/// end bounding the speed along it.
double pathMotionRate(const dynamics::RigidBody& body, double radius, double duration,
                      const Eigen::Vector3d& gravity = Eigen::Vector3d::Zero());

}  // namespace polysim::sim
