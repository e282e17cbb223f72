#pragma once
// Closest points between two line segments (Ericson, Real-Time Collision Detection, 5.1.9).

#include <Eigen/Core>

namespace polysim::collision {

struct SegmentClosestPoints {
  Eigen::Vector3d onFirst, onSecond;
  double distance = 0.0;  // m
  /// The points' parameters: onFirst = p0 + s u, onSecond = q0 + t v; exactly 0 or 1 at
  /// a segment's end (recomputed from a point, an end's parameter may miss by round-off).
  double s = 0.0, t = 0.0;
};

/// The closest points of segments p0 + s u and q0 + t v, s and t in [0, 1]. Parallel
/// segments give one of the closest pairs. Zero-length segments are allowed.
SegmentClosestPoints closestPointsOnSegments(const Eigen::Vector3d& p0, const Eigen::Vector3d& u,
                                             const Eigen::Vector3d& q0, const Eigen::Vector3d& v);

}  // namespace polysim::collision
