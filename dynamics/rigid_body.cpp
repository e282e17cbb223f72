#include "dynamics/rigid_body.h"

#include "dynamics/settings.h"

namespace polysim::dynamics {

RigidBody RigidBody::dynamic(const MassProperties& props) {
  RigidBody b;
  b.mass = props.mass;
  b.inverseMass = 1.0 / props.mass;
  b.centerOfMassLocal = props.centerOfMass;
  b.inertiaLocal = props.inertia;
  b.inverseInertiaLocal = props.inertia.inverse();
  return b;
}

RigidBody RigidBody::fixed() {
  RigidBody b;
  b.isStatic = true;
  return b;
}

Eigen::Matrix3d RigidBody::inverseInertiaWorld() const {
  const Eigen::Matrix3d R = orientation.toRotationMatrix();
  return R * inverseInertiaLocal * R.transpose();
}

void RigidBody::applyImpulse(const Eigen::Vector3d& J, const Eigen::Vector3d& p) {
  if (isStatic) return;
  velocity += inverseMass * J;
  angularVelocity += inverseInertiaWorld() * (p - centerOfMass()).cross(J);
}

void RigidBody::applyPushImpulse(const Eigen::Vector3d& J, const Eigen::Vector3d& p) {
  if (isStatic) return;
  pushVelocity += inverseMass * J;
  pushAngularVelocity += inverseInertiaWorld() * (p - centerOfMass()).cross(J);
}

bool atRest(const Eigen::Vector3d& velocity, const Eigen::Vector3d& angularVelocity, double size) {
  return velocity.norm() < kRestSpeed && angularVelocity.norm() * size < kRestSpeed;
}

double RigidBody::kineticEnergy() const {
  if (isStatic) return 0.0;
  const Eigen::Matrix3d R = orientation.toRotationMatrix();
  const Eigen::Vector3d wLocal = R.transpose() * angularVelocity;
  return 0.5 * mass * velocity.squaredNorm() + 0.5 * wLocal.dot(inertiaLocal * wLocal);
}

Eigen::Isometry3d RigidBody::pose() const {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = orientation.toRotationMatrix();
  X.translation() = position;
  return X;
}

}  // namespace polysim::dynamics
