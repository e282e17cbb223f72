#pragma once
// How thin an object is: the least distance through it, which bounds how far it may move
// between two tests before something could pass through it unseen.

#include "collision/polygon_mesh.h"
#include "collision/voxel_grid.h"

namespace polysim::collision {

/// The least, over the faces, of the distance from the face's centroid straight inwards
/// (along -normal) to the next face hit (m). Rays that leave an open mesh without
/// hitting anything do not count; infinity when no ray hits (a single plane). Rays are
/// cast through the grid's content boxes.
double minimumThickness(const PolygonMesh& mesh, const VoxelGrid& grid);

}  // namespace polysim::collision
