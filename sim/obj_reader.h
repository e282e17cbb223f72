#pragma once
// Wavefront OBJ files as polygon meshes: vertices ("v") and faces ("f"); texture
// coordinates, normals, groups and materials are ignored.

#include <string>

#include "collision/polygon_mesh.h"

namespace polysim::sim {

/// Reads `path`. Throws std::runtime_error naming the file and line of the first problem
/// (unreadable file, malformed number, index out of range).
collision::MeshData readObj(const std::string& path);

}  // namespace polysim::sim
