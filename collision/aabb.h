#pragma once
// Axis-aligned boxes moved between frames.

#include <Eigen/Geometry>

namespace polysim::collision {

/// The world-axis box enclosing `local` (a box in the frame of X_WO) placed by X_WO: the
/// transformed centre, and half extents |R| h. Exact for the rotated box's corners.
inline Eigen::AlignedBox3d transformBox(const Eigen::Isometry3d& X_WO, const Eigen::AlignedBox3d& local) {
  const Eigen::Vector3d centre = X_WO * local.center();
  const Eigen::Vector3d half = X_WO.linear().cwiseAbs() * (0.5 * local.sizes());
  return Eigen::AlignedBox3d(centre - half, centre + half);
}

/// The box grown by `margin` (m) on every side.
inline Eigen::AlignedBox3d grow(const Eigen::AlignedBox3d& box, double margin) {
  return Eigen::AlignedBox3d(box.min().array() - margin, box.max().array() + margin);
}

}  // namespace polysim::collision
