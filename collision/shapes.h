#pragma once
// The built-in shapes of the scene format as polygon meshes, in their own frame with the
// origin at the shape's centre.

#include "collision/polygon_mesh.h"

namespace polysim::collision {

/// A cuboid of the given full side lengths (m): 8 vertices, 6 quadrilateral faces.
MeshData makeBox(const Eigen::Vector3d& size);

/// A geodesic sphere: an icosahedron whose triangles are split in four `subdivisions`
/// times (20 * 4^n triangles), vertices on the sphere of the given radius (m).
MeshData makeIcosphere(double radius, int subdivisions);

/// A flat rectangular floor of size sx by sy (m) at z = 0, facing +z, split into k by k
/// squares of two triangles each (2 k^2 triangles); an open mesh, for static terrain.
MeshData makeTriangulatedFloor(double sx, double sy, int k);

}  // namespace polysim::collision
