#pragma once
// Which directions a mesh can be touched from at one of its features: the feature's
// normal cone. Where polygon pairs report a contact at the rim of a face, or the same
// contact several times with different normals (two boxes stacked edge on edge), it
// tells the true normal from the artefacts.

#include <Eigen/Core>

#include "collision/contact.h"
#include "collision/polygon_mesh.h"

namespace polysim::collision {

/// True when the mesh can be touched at `feature` by something lying on the `outward`
/// side (a unit vector in the mesh's frame, pointing out of the mesh): no point of the
/// faces around the feature rises more than eps + kNormalConeSlack times its distance
/// out of the plane through the feature square to `outward`. A face admits its normal,
/// an edge the wedge between its faces' normals, a vertex the cone among its faces'.
/// Features at a reflex (concave) edge admit every direction: there the normal is not
/// the feature's to decide.
bool inNormalCone(const PolygonMesh& mesh, const Feature& feature, const Eigen::Vector3d& outward, double eps);

}  // namespace polysim::collision
