#include "sim/obj_reader.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace polysim::sim {
namespace {

// Every statement of the OBJ format (Wavefront's appendix B1), so that a real file with
// curves or materials is read, and a file of some other kind is not taken for an empty one.
constexpr std::array kObjStatements = {
    "v", "vt", "vn", "vp", "f", "l", "p",                                        // vertex data, elements
    "g", "o", "s", "mg", "mtllib", "usemtl", "maplib", "usemap",                 // grouping, display
    "lod", "shadow_obj", "trace_obj", "bevel", "c_interp", "d_interp",           // render attributes
    "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim",    // free-form geometry
    "hole", "scrv", "sp", "end", "con", "ctech", "stech", "call", "csh"};

bool isObjStatement(const std::string& tag) {
  return std::find(kObjStatements.begin(), kObjStatements.end(), tag) != kObjStatements.end();
}

// Control characters other than white space: what text never holds and binary data does.
bool looksBinary(const std::string& line) {
  return std::any_of(line.begin(), line.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return (u < 0x20 && c != '\t' && c != '\r' && c != '\f' && c != '\v') || u == 0x7f;
  });
}

// What a line starts with, cut to a readable length, for a message.
std::string shownText(const std::string& text) {
  constexpr size_t kShown = 40;
  return "\"" + (text.size() > kShown ? text.substr(0, kShown) + "..." : text) + "\"";
}

}  // namespace

collision::MeshData readObj(std::istream& in) {
  collision::MeshData mesh;
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    auto fail = [&](const std::string& what) {
      throw std::runtime_error("line " + std::to_string(lineNo) + ": " + what);
    };
    if (looksBinary(line)) fail("binary data, not OBJ text");
    std::istringstream words(line);
    std::string tag;
    if (!(words >> tag) || tag[0] == '#') continue;
    if (!isObjStatement(tag)) fail(shownText(tag) + " is not an OBJ statement");
    if (tag == "v") {
      Eigen::Vector3d v;
      if (!(words >> v.x() >> v.y() >> v.z())) fail("a vertex needs three numbers");
      mesh.vertices.push_back(v);
    } else if (tag == "f") {
      std::vector<int> face;
      std::string corner;
      const int n = static_cast<int>(mesh.vertices.size());
      while (words >> corner) {
        // "i", "i/t", "i//n" or "i/t/n": the vertex index comes first; negative counts
        // back from the last vertex read so far.
        int index = 0;
        try {
          size_t used = 0;
          index = std::stoi(corner, &used);
          if (used < corner.size() && corner[used] != '/') fail("bad face index " + shownText(corner));
        } catch (const std::logic_error&) {
          fail("bad face index " + shownText(corner));
        }
        if (index == 0) fail("face index 0 (OBJ indices start at 1)");
        if (index < -n) fail("face index " + corner + " reaches back past the first vertex (" + std::to_string(n) + " read so far)");
        face.push_back(index > 0 ? index - 1 : n + index);
      }
      mesh.faces.push_back(std::move(face));
    }
  }
  const int n = static_cast<int>(mesh.vertices.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int index : mesh.faces[f])
      if (index >= n)
        throw std::runtime_error("face " + std::to_string(f + 1) + " uses vertex " + std::to_string(index + 1) +
                                 ", but the file has " + std::to_string(n));
  if (mesh.vertices.empty() || mesh.faces.empty())
    throw std::runtime_error(std::string("not an OBJ mesh: it has no ") + (mesh.vertices.empty() ? "vertex (\"v\" line)" : "face (\"f\" line)"));
  return mesh;
}

collision::MeshData readObjFile(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw std::runtime_error(std::filesystem::exists(path, error) ? "not a file, so not an OBJ mesh" : "no such file");
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot be read");
  return readObj(in);
}

}  // namespace polysim::sim
