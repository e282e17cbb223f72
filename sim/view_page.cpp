#include "sim/view_page.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "sim/scene.h"
#include "sim/view_data.h"
#include "sim/viewer_assets.h"
#include "sim/whole_file.h"

namespace polysim::sim {
namespace {

std::string readThreeJs(const std::string& file) {
  const std::string path = std::string(POLYSIM_THREE_DIR) + "/" + file;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error(path + ": not found; polysim view inlines three.js from Debian's libjs-three "
                                    "(apt-get install libjs-three)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Replaces the one marker `/*{{NAME}}*/` of the page by `text`.
void fill(std::string& page, const std::string& name, const std::string& text) {
  const std::string marker = "/*{{" + name + "}}*/";
  const size_t at = page.find(marker);
  if (at == std::string::npos) throw std::logic_error("the viewer page has no " + marker);
  page.replace(at, marker.size(), text);
}

// JSON inside a <script> element: "</" would end the element early (a body named
// "</script>"); "<\/" is the same string to JSON.
std::string scriptSafe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (size_t i = 0; i < json.size(); ++i) {
    out += json[i];
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') out += '\\';
  }
  return out;
}

}  // namespace

ViewPage writeViewPage(const ViewOptions& options) {
  if (options.logs.empty()) throw std::invalid_argument("polysim view: no step log given");
  std::string scenePath = options.scene.value_or(sceneNamedByLog(options.logs.front()));
  if (scenePath.empty())
    throw std::runtime_error(options.logs.front() + ": names no scene (a log from an older polysim); give it with --scene");
  const Scene scene = loadScene(scenePath);
  nlohmann::ordered_json data;
  data["scene"] = sceneToViewJson(scene);
  data["runs"] = nlohmann::ordered_json::array();
  ViewPage written;
  for (const std::string& log : options.logs) {
    data["runs"].push_back(logToViewJson(log, scene));
    if (!data["runs"].back()["cutShort"].is_null()) written.warnings.push_back(data["runs"].back()["cutShort"]);
  }

  std::string page = viewer::kPage;
  fill(page, "THREE", readThreeJs("three.min.js"));
  fill(page, "ORBIT", readThreeJs("examples/js/controls/OrbitControls.js"));
  fill(page, "DRAWING", viewer::kDrawing);
  fill(page, "VIEWER", viewer::kScript);
  fill(page, "DATA", scriptSafe(data.dump()));  // last: the data may hold any marker's text
  const std::string out =
      options.out.empty() ? std::filesystem::path(options.logs.front()).replace_extension(".html").string() : options.out;
  for (const std::string& input : options.logs)
    if (std::filesystem::exists(out) && std::filesystem::equivalent(out, input))
      throw std::invalid_argument("--out: " + out + " is the step log itself");
  writeWholeFile(out, "the view page", [&page](std::ostream& file) { file << page; });
  written.path = out;
  return written;
}

}  // namespace polysim::sim
