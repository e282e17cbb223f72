#pragma once
// The polygon tests see one polygon pair at a time, so a box on a triangulated floor
// yields one area piece per triangle, and every edge and vertex on that area again as
// lines and points. Reduction turns these into the contacts a user expects: each
// coplanar set of area pieces merged into one polygon, collinear line pieces joined,
// and lines and points dropped when they lie on a reported area or line.

#include <Eigen/Core>
#include <vector>

#include "collision/contact.h"
#include "collision/polygon_mesh.h"

namespace polysim::collision {

/// The pair's meshes and world orientations, to tell which of several disagreeing normals
/// of one contact is true (normal_cone.h).
struct PairGeometry {
  const PolygonMesh* meshA = nullptr;
  const PolygonMesh* meshB = nullptr;
  Eigen::Matrix3d R_WA = Eigen::Matrix3d::Identity(), R_WB = Eigen::Matrix3d::Identity();
  /// The pair's verdict is the polygons' own measure, face pair by face pair (objects
  /// that are not convex; intersection.cpp). A point sunk along a normal both its
  /// features admit is then held along that normal: it keeps a contact of its own beside
  /// the one along the normal most of its pieces admit (a cup's inner rim corner inside
  /// the corner of another cup's walls, behind each wall), and is not dropped for lying
  /// on a line or area along another normal (a bottom edge along an inner wall, dipping
  /// under the rim edge at the corner). That measure reads the point that deep, and a
  /// contact along another normal would let it sink until the pair is found
  /// interpenetrating at the very start of the next step.
  bool sunkHeldAlongEachFace = false;
};

/// The contacts of one object pair with every contact reported once. `eps` (m) is the
/// contact tolerance: pieces within eps of each other are the same contact. Pieces joined
/// into one line or point keep their common normal; when their normals disagree (where
/// corners and edges of the two objects coincide, each polygon pair proposes its own
/// face's normal), the contact takes the proposed normal that the most of the pieces'
/// features admit in their normal cones (with `geometry`; without, the mean normal).
std::vector<Contact> reduceContacts(const std::vector<Contact>& raw, double eps, const PairGeometry* geometry = nullptr);

}  // namespace polysim::collision
