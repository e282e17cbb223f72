#include "sim/view_data.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include "sim/log_fields.h"

namespace polysim::sim {
namespace {

using nlohmann::ordered_json;

// Floats per dynamic body and frame in `poses`: position, orientation, velocity.
constexpr int kPoseFloats = 10;

ordered_json numbersOrNull(const std::vector<double>& values) {
  ordered_json out = ordered_json::array();
  for (double v : values) out.push_back(std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr));
  return out;
}

// The step lines of a log, parsed. A last line without its end of line is a run stopped
// while writing it (killed, or a full disk): it is left out, and `cutShort` says so.
std::vector<ordered_json> readLines(const std::string& path, std::string& cutShort) {
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(path + ": not a file (a step log is one)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read it");
  std::vector<ordered_json> lines;
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    if (line.empty()) continue;
    const std::string where = path + " line " + std::to_string(lineNo);
    if (in.eof()) {
      cutShort = where + ": cut short (the run stopped while writing it); the page ends at the step before";
      break;
    }
    try {
      lines.push_back(ordered_json::parse(line));
    } catch (const std::exception&) {
      throw std::runtime_error(where + ": not JSON, so not a step of a polysim step log");
    }
  }
  if (lines.empty()) throw std::runtime_error(path + ": holds no step (not a polysim step log, or empty)");
  return lines;
}

// A step's contacts as the page draws them: per pair a and b, per contact its type,
// normal and points (the gaps and status stay in the log).
ordered_json contactsToDraw(const LogFields& step) {
  ordered_json pairs = ordered_json::array();
  const ordered_json& list = step.array("contacts");
  for (size_t i = 0; i < list.size(); ++i) {
    const LogFields pair(list[i], step.where() + ": contact pair " + std::to_string(i));
    ordered_json contacts = ordered_json::array();
    const ordered_json& cs = pair.array("contacts");
    for (size_t k = 0; k < cs.size(); ++k) {
      const LogFields c(cs[k], pair.where() + ": contact " + std::to_string(k));
      const ordered_json& points = c.array("points");
      for (size_t j = 0; j < points.size(); ++j)
        if (!points[j].is_array() || points[j].size() != 3 || !points[j][0].is_number() || !points[j][1].is_number() ||
            !points[j][2].is_number())
          throw std::runtime_error(c.where() + ": point " + std::to_string(j) + " is not 3 numbers");
      contacts.push_back({{"type", c.text("type")}, {"normal", c.numbers("normal", 3)}, {"points", points}});
    }
    pairs.push_back({{"a", pair.text("a")}, {"b", pair.text("b")}, {"contacts", contacts}});
  }
  return pairs;
}

}  // namespace

std::string base64(const unsigned char* bytes, size_t size) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (size_t i = 0; i < size; i += 3) {
    const unsigned a = bytes[i], b = i + 1 < size ? bytes[i + 1] : 0u, c = i + 2 < size ? bytes[i + 2] : 0u;
    const unsigned triple = (a << 16) | (b << 8) | c;
    out += digits[(triple >> 18) & 63];
    out += digits[(triple >> 12) & 63];
    out += i + 1 < size ? digits[(triple >> 6) & 63] : '=';
    out += i + 2 < size ? digits[triple & 63] : '=';
  }
  return out;
}

ordered_json sceneToViewJson(const Scene& scene) {
  ordered_json bodies = ordered_json::array();
  for (const BodySpec& b : scene.bodies) {
    ordered_json vertices = ordered_json::array();
    for (const Eigen::Vector3d& v : b.mesh.vertices) vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
    bodies.push_back({{"name", b.name},
                      {"static", b.isStatic},
                      {"vertices", vertices},
                      {"faces", b.mesh.faces},
                      {"position", {b.position.x(), b.position.y(), b.position.z()}},
                      {"orientation", {b.orientation.w(), b.orientation.x(), b.orientation.y(), b.orientation.z()}}});
  }
  return {{"name", scene.name}, {"bodies", bodies}};
}

ordered_json logToViewJson(const std::string& logPath, const Scene& scene) {
  std::string cutShort;
  const std::vector<ordered_json> lines = readLines(logPath, cutShort);
  std::map<std::string, int> slotOf;  // dynamic body name -> its place in a frame
  std::vector<int> dynamic;
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].isStatic) {
      slotOf[scene.bodies[i].name] = static_cast<int>(dynamic.size());
      dynamic.push_back(static_cast<int>(i));
    }
  const size_t frames = lines.size() + 1, bodies = dynamic.size();
  std::vector<float> poses(frames * bodies * kPoseFloats, 0.0f);
  for (size_t k = 0; k < bodies; ++k) {  // frame 0: the scene's initial state
    const BodySpec& b = scene.bodies[static_cast<size_t>(dynamic[k])];
    const double state[kPoseFloats] = {b.position.x(), b.position.y(), b.position.z(), b.orientation.w(), b.orientation.x(),
                                       b.orientation.y(), b.orientation.z(), b.velocity.x(), b.velocity.y(), b.velocity.z()};
    for (int f = 0; f < kPoseFloats; ++f) poses[k * kPoseFloats + static_cast<size_t>(f)] = static_cast<float>(state[f]);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> times{0.0}, energy{nan}, penetration{0.0}, events;
  // Contacts, kept once per run of frames that share them (a resting or sleeping scene
  // repeats the same contacts every step): sets, and the set of each frame.
  ordered_json contactSets = ordered_json::array({ordered_json::array()});
  std::vector<size_t> contactSetOf{0};
  bool anyContacts = false;
  for (size_t n = 0; n < lines.size(); ++n) {
    const LogFields step(lines[n], logPath + " line " + std::to_string(n + 1));
    times.push_back(step.number("t"));
    energy.push_back(step.has("energy") ? step.number("energy") : nan);
    penetration.push_back(step.has("penetration") ? step.number("penetration") : nan);
    const ordered_json& stepEvents = step.array("events");
    for (size_t e = 0; e < stepEvents.size(); ++e)
      events.push_back(LogFields(stepEvents[e], step.where() + ": event " + std::to_string(e)).number("time"));
    anyContacts = anyContacts || step.has("contacts");
    const ordered_json drawn = step.has("contacts") ? contactsToDraw(step) : ordered_json::array();
    if (drawn != contactSets.back()) contactSets.push_back(drawn);
    contactSetOf.push_back(contactSets.size() - 1);
    const ordered_json& list = step.array("bodies");
    std::vector<char> seen(bodies, 0);
    for (size_t j = 0; j < list.size(); ++j) {
      const LogFields body(list[j], step.where() + ": body " + std::to_string(j));
      const std::string name = body.text("name");
      const auto slot = slotOf.find(name);
      if (slot == slotOf.end())
        throw std::runtime_error(body.where() + ": \"" + name + "\" is not a dynamic body of " + scene.file +
                                 " (the log is not of this scene)");
      std::vector<double> state = body.numbers("position", 3);
      for (const char* key : {"orientation", "velocity"}) {
        const std::vector<double> more = body.numbers(key, key[0] == 'o' ? 4 : 3);
        state.insert(state.end(), more.begin(), more.end());
      }
      float* out = &poses[((n + 1) * bodies + static_cast<size_t>(slot->second)) * kPoseFloats];
      for (int f = 0; f < kPoseFloats; ++f) out[f] = static_cast<float>(state[static_cast<size_t>(f)]);
      seen[static_cast<size_t>(slot->second)] = 1;
    }
    for (size_t k = 0; k < bodies; ++k)
      if (!seen[k])
        throw std::runtime_error(step.where() + ": no body \"" + scene.bodies[static_cast<size_t>(dynamic[k])].name +
                                 "\" (the log is not of " + scene.file + ")");
  }
  static_assert(std::numeric_limits<float>::is_iec559, "the page reads IEEE float32");
  std::vector<unsigned char> bytes(poses.size() * sizeof(float));
  std::memcpy(bytes.data(), poses.data(), bytes.size());  // little-endian on every machine polysim builds for
  return {{"label", std::filesystem::path(logPath).stem().string()},
          {"frames", frames},
          {"dynamic", dynamic},
          {"times", times},
          {"energy", numbersOrNull(energy)},
          {"penetration", numbersOrNull(penetration)},
          {"events", events},
          {"poses", base64(bytes.data(), bytes.size())},
          {"contactSets", anyContacts ? contactSets : ordered_json(nullptr)},
          {"contactSetOf", contactSetOf},
          {"cutShort", cutShort.empty() ? ordered_json(nullptr) : ordered_json(cutShort)}};
}

std::string sceneNamedByLog(const std::string& logPath) {
  std::ifstream in(logPath);
  std::string line;
  if (!std::getline(in, line)) return "";
  const ordered_json first = ordered_json::parse(line, nullptr, false);
  if (first.is_discarded() || !first.is_object() || !first.contains("scene") || !first["scene"].is_string()) return "";
  return first["scene"].get<std::string>();
}

}  // namespace polysim::sim
