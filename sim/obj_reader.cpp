#include "sim/obj_reader.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace polysim::sim {

collision::MeshData readObj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  collision::MeshData mesh;
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    auto fail = [&](const std::string& what) {
      throw std::runtime_error(path + " line " + std::to_string(lineNo) + ": " + what);
    };
    if (tag == "v") {
      Eigen::Vector3d v;
      if (!(words >> v.x() >> v.y() >> v.z())) fail("a vertex needs three numbers");
      mesh.vertices.push_back(v);
    } else if (tag == "f") {
      std::vector<int> face;
      std::string corner;
      while (words >> corner) {
        // "i", "i/t", "i//n" or "i/t/n": the vertex index comes first; negative counts back.
        int index = 0;
        try {
          size_t used = 0;
          index = std::stoi(corner, &used);
          if (used < corner.size() && corner[used] != '/') fail("bad face index \"" + corner + "\"");
        } catch (const std::logic_error&) {
          fail("bad face index \"" + corner + "\"");
        }
        if (index == 0) fail("face index 0 (OBJ indices start at 1)");
        const int n = static_cast<int>(mesh.vertices.size());
        face.push_back(index > 0 ? index - 1 : n + index);
      }
      mesh.faces.push_back(std::move(face));
    }
  }
  return mesh;
}

}  // namespace polysim::sim
