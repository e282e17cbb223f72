// libFuzzer target: the OBJ reader on any text. It either returns a mesh or throws
// std::runtime_error with a message (line number or "not an OBJ mesh"); a mesh that
// validateMesh accepts builds a PolygonMesh. Anything else (a crash, another exception,
// a sanitizer report) is a finding.

#include <sstream>
#include <stdexcept>
#include <string>

#include "collision/polygon_mesh.h"
#include "sim/obj_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream text(std::string(reinterpret_cast<const char*>(data), size));
  polysim::collision::MeshData mesh;
  try {
    mesh = polysim::sim::readObj(text);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).empty()) std::abort();  // every refusal says why
    return 0;
  }
  if (polysim::collision::validateMesh(mesh, false).empty()) polysim::collision::PolygonMesh built(mesh);
  return 0;
}
