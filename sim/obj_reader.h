#pragma once
// Wavefront OBJ files as polygon meshes: vertices ("v") and faces ("f"); the other
// statements of the format (texture coordinates, normals, groups, materials, curves) are
// read past. A file that is not an OBJ mesh at all (a folder, binary data, text whose
// lines are not OBJ statements, no vertex or face) is said to be none.

#include <istream>
#include <string>

#include "collision/polygon_mesh.h"

namespace polysim::sim {

/// Reads the OBJ text in `in`. Throws std::runtime_error of the form "line N: what" for
/// the first problem (a line that is not an OBJ statement, binary data, a malformed
/// number, a face index that is 0 or out of range), or "not an OBJ mesh: ..." when it
/// holds no vertex or no face. Face indices are returned 0-based; negative ones (counted
/// back from the last vertex read) are resolved.
collision::MeshData readObj(std::istream& in);

/// Reads the file at `path` as above, and says so when `path` is not a readable regular
/// file. Messages do not repeat the path: the caller names the file as its user wrote it.
collision::MeshData readObjFile(const std::string& path);

}  // namespace polysim::sim
