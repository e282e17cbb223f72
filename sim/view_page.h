#pragma once
// `polysim view`: one self-contained HTML page replaying step logs of a scene in the
// browser (three.js inlined; no server, no network).

#include <optional>
#include <string>
#include <vector>

namespace polysim::sim {

struct ViewOptions {
  std::vector<std::string> logs;     // one log, or several of the same scene shown side by side
  std::optional<std::string> scene;  // default: the scene the first log names (its first line)
  std::string out;                   // default: the first log with the extension .html
};

struct ViewPage {
  std::string path;
  std::vector<std::string> warnings;  // logs cut short: each is shown up to its last whole step
};

/// Reads the scene and the logs (view_data.h), and writes the page whole (or nothing) to
/// the output path, which it returns. Throws SceneError for a bad scene and
/// std::runtime_error naming the file, line and field for a bad or mismatched log, when
/// no scene is given or named, and when three.js (Debian's libjs-three) is missing.
ViewPage writeViewPage(const ViewOptions& options);

}  // namespace polysim::sim
