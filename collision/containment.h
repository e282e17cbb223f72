#pragma once
// Containment: an object wholly inside a closed object meets none of its polygons, so the
// polygon tests alone call the pair separate. The inside test here finds it.

#include <Eigen/Core>
#include <optional>

#include "collision/object.h"
#include "collision/polygon_mesh.h"

namespace polysim::collision {

/// True when point p (the mesh's frame) is inside the closed `mesh`: a ray from p crosses
/// its surface an odd number of times. A ray that grazes an edge or a vertex is cast
/// again in another direction.
bool insideClosedMesh(const PolygonMesh& mesh, const Eigen::Vector3d& p);

/// For a pair none of whose polygons meet within the tolerance: how deep (m: its deepest
/// vertex's distance to the surface of `outer`) the closed `outer` holds `inner`, or
/// empty when it does not. Surfaces that do not meet leave inner wholly
/// inside or wholly outside, so one vertex decides. Empty at once when outer is open or
/// inner's container is not inside outer's: the test costs nothing for most pairs.
std::optional<double> containmentDepth(const ObjNode& inner, const ObjNode& outer);

}  // namespace polysim::collision
