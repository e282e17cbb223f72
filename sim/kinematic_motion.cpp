#include "sim/kinematic_motion.h"

namespace polysim::sim {

void kinematicPose(double s, const void* info, Eigen::Isometry3d& X_WO) {
  const KinematicMotion& m = *static_cast<const KinematicMotion*>(info);
  const double t = s * m.interval;
  const double angle = m.angularVelocity.norm() * t;
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
  if (angle > 0) turn = Eigen::AngleAxisd(angle, m.angularVelocity.normalized()).toRotationMatrix();
  X_WO.linear() = turn * m.start.linear();
  X_WO.translation() = m.start.translation() + t * m.velocity;
}

double kinematicMotionBound(const KinematicMotion& motion, const collision::PolygonMesh& mesh) {
  double radius = 0.0;
  for (const Eigen::Vector3d& v : mesh.vertices()) radius = std::max(radius, v.norm());
  return motion.interval * (motion.velocity.norm() + motion.angularVelocity.norm() * radius);
}

}  // namespace polysim::sim
