#include "sim/body_path.h"

#include "dynamics/integrator.h"

namespace polysim::sim {

void bodyPathPose(double s, const void* info, Eigen::Isometry3d& X_WO) {
  const BodyPath& path = *static_cast<const BodyPath*>(info);
  X_WO = dynamics::poseAfter(*path.body, s * path.duration, path.gravity);
}

double pathMotionBound(const dynamics::RigidBody& body, double radius, double duration, const Eigen::Vector3d& gravity) {
  const double speed = (body.velocity + body.pushVelocity).norm();
  const double spin = (body.angularVelocity + body.pushAngularVelocity).norm();
  return duration * (speed + 0.5 * gravity.norm() * duration + spin * radius);
}

double pathMotionRate(const dynamics::RigidBody& body, double radius, double duration, const Eigen::Vector3d& gravity) {
  const double speed = (body.velocity + body.pushVelocity).norm();
  const double spin = (body.angularVelocity + body.pushAngularVelocity).norm();
  return duration * (speed + gravity.norm() * duration + spin * radius);
}

}  // namespace polysim::sim
