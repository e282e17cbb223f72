#include "sim/json_text.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace polysim::sim {
namespace {

using json = nlohmann::json;

// Where the parser is: per open object its current key, per open array how many of its
// elements are complete (the index of the one being read).
class JsonPath {
 public:
  bool follow(json::parse_event_t event, const json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: levels_.push_back({false, "", 0}); break;
      case json::parse_event_t::array_start: levels_.push_back({true, "", 0}); break;
      case json::parse_event_t::key: levels_.back().key = parsed.get<std::string>(); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        levels_.pop_back();
        elementDone();
        break;
      case json::parse_event_t::value: elementDone(); break;
    }
    return true;  // keep everything
  }
  std::string text() const {
    std::string path;
    for (const Level& level : levels_)
      path += level.isArray ? "[" + std::to_string(level.done) + "]" : (path.empty() ? "" : ".") + level.key;
    return path.empty() ? "the top level" : path;
  }

 private:
  struct Level {
    bool isArray;
    std::string key;
    int done;
  };
  void elementDone() {
    if (!levels_.empty() && levels_.back().isArray) ++levels_.back().done;
  }
  std::vector<Level> levels_;
};

// nlohmann's what() starts with "[json.exception.parse_error.101] "; keep the sentence.
std::string sentence(const json::exception& e) {
  const std::string what = e.what();
  const size_t end = what.find("] ");
  return what.substr(end == std::string::npos ? 0 : end + 2);
}

}  // namespace

json parseJsonText(std::istream& in) {
  JsonPath path;
  try {
    return json::parse(in, [&path](int, json::parse_event_t event, json& parsed) { return path.follow(event, parsed); });
  } catch (const json::out_of_range& e) {  // a number beyond a double: nlohmann gives no place
    throw std::runtime_error(sentence(e) + " at " + path.text());
  } catch (const json::exception& e) {
    throw std::runtime_error(sentence(e));
  }
}

}  // namespace polysim::sim
