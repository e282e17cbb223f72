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

void appendContactPoints(int a, int b, const std::vector<collision::Contact>& contacts, const PairMaterial& material,
                         std::vector<dynamics::ContactPoint>& out) {
  using Kind = collision::Feature::Kind;
  for (const collision::Contact& c : contacts) {
    const int manifold = static_cast<int>(out.size());  // unique: the index of its first point
    const bool faceOfA = c.featureA.kind == Kind::Face, faceOfB = c.featureB.kind == Kind::Face;
    const double turnWithA = faceOfA == faceOfB ? 0.5 : faceOfA ? 1.0 : 0.0;
    for (size_t i = 0; i < c.points.size(); ++i)
      out.push_back({a, b, c.points[i], c.normal, c.gapAt(i), material.restitution, material.friction, manifold, turnWithA});
  }
}

}  // namespace polysim::sim
