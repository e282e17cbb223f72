#pragma once
// Kinematic motion for `polysim toc`: constant velocity and constant world-frame angular
// velocity about the body's position, as a collision-module update function (ctrans).

#include <Eigen/Geometry>

#include "collision/polygon_mesh.h"

namespace polysim::sim {

struct KinematicMotion {
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();  // pose at time 0
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // m/s, world
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();   // rad/s, world, about the body's position
  double interval = 0.0;                                       // s: the length of [0, 1]
};

/// ctrans for a KinematicMotion: the pose at time s * interval.
void kinematicPose(double s, const void* info, Eigen::Isometry3d& X_WO);

/// How far any vertex of `mesh` can move over the interval (m): |v| T plus the rotation
/// angle times the farthest vertex's distance from the body's origin.
double kinematicMotionBound(const KinematicMotion& motion, const collision::PolygonMesh& mesh);

}  // namespace polysim::sim
