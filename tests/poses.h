#pragma once
// Poses for tests and benchmarks (no GoogleTest dependency, so benchmarks can use it).

#include <Eigen/Geometry>

namespace polysim::test {

inline Eigen::Isometry3d pose(const Eigen::Vector3d& p, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

inline Eigen::Matrix3d rot(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

}  // namespace polysim::test
