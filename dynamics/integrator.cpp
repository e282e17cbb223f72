#include "dynamics/integrator.h"

namespace polysim::dynamics {

void integrateVelocity(RigidBody& body, const Eigen::Vector3d& gravity, double dt) {
  if (!body.isStatic) body.velocity += gravity * dt;
}

namespace {

// The orientation and frame origin after time s along the step's path.
void pathAfter(const RigidBody& body, double s, const Eigen::Vector3d& gravity, Eigen::Quaterniond& q,
               Eigen::Vector3d& origin) {
  const Eigen::Vector3d w = body.angularVelocity + body.pushAngularVelocity;
  const double angle = w.norm() * s;
  q = body.orientation;
  if (angle > 0) q = (Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized())) * q).normalized();
  origin = body.centerOfMass() + (body.velocity + body.pushVelocity) * s + (0.5 * s * s) * gravity -
           q * body.centerOfMassLocal;
}

}  // namespace

Eigen::Isometry3d poseAfter(const RigidBody& body, double s, const Eigen::Vector3d& gravity) {
  if (body.isStatic) return body.pose();
  Eigen::Quaterniond q;
  Eigen::Vector3d origin;
  pathAfter(body, s, gravity, q, origin);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = origin;
  return X;
}

void advancePose(RigidBody& body, double s, const Eigen::Vector3d& gravity) {
  if (body.isStatic) return;
  Eigen::Quaterniond q;
  Eigen::Vector3d origin;
  pathAfter(body, s, gravity, q, origin);  // into locals: pathAfter reads the body's current pose
  body.orientation = q;
  body.position = origin;
  body.velocity += gravity * s;
}

}  // namespace polysim::dynamics
