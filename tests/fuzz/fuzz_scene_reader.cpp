// libFuzzer target: the scene reader and the start-state check on any text. A scene is
// read, or refused with a SceneError naming the file; anything else (a crash, another
// exception, a sanitizer report) is a finding.

#include <sstream>
#include <string>

#include "sim/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string kName = "/nonexistent/fuzzed_scene.json";  // OBJ files resolve nowhere
  std::istringstream text(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const polysim::sim::Scene scene = polysim::sim::readScene(text, kName);
    polysim::sim::checkInitialState(scene);
  } catch (const polysim::sim::SceneError& e) {
    if (std::string(e.what()).rfind(kName + ": ", 0) != 0) std::abort();  // every line names the file
  }
  return 0;
}
