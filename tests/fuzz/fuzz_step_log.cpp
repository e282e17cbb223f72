// libFuzzer target: the step-log readers (polysim log, every query; polysim view's) on any
// bytes. Each reads the log or throws std::runtime_error naming the file; anything else
// (a crash, another exception, a sanitizer report) is a finding.

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "sim/log_inspect.h"
#include "sim/scene.h"
#include "sim/view_data.h"

namespace {

void mustNameTheFile(const std::runtime_error& e, const std::string& path) {
  if (std::string(e.what()).rfind(path, 0) != 0) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/polysim_fuzz_step_log_" + std::to_string(getpid()) + ".jsonl";
  static const polysim::sim::Scene scene = polysim::sim::loadScene(POLYSIM_SCENES_DIR "/drop_box.json");
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  for (int query = 0; query < 4; ++query) {
    polysim::sim::LogQuery q;
    q.events = query & 1;
    q.table = query & 2;
    if (query == 3) q.body = "box";
    std::ostringstream out;
    try {
      polysim::sim::inspectLog(path, q, out);
    } catch (const std::runtime_error& e) {
      mustNameTheFile(e, path);
    }
  }
  try {
    (void)polysim::sim::logToViewJson(path, scene);
  } catch (const std::runtime_error& e) {
    mustNameTheFile(e, path);
  }
  return 0;
}
