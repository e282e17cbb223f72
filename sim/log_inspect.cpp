#include "sim/log_inspect.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "sim/log_fields.h"

namespace polysim::sim {
namespace {

using nlohmann::ordered_json;

// One pair of an event as "a/b:kinds", or empty when `body` is given and not in it.
std::string pairText(const LogFields& pair, const std::optional<std::string>& body) {
  const std::string a = pair.text("a"), b = pair.text("b");
  if (body && a != *body && b != *body) return "";
  std::string kinds;
  const ordered_json& contacts = pair.has("contacts") ? pair.array("contacts") : ordered_json::array();
  for (size_t k = 0; k < contacts.size(); ++k)
    kinds += (kinds.empty() ? "" : "+") + LogFields(contacts[k], pair.where() + ": contact " + std::to_string(k)).text("type");
  return a + "/" + b + ":" + (kinds.empty() ? pair.text("status") : kinds);
}

// The rows for one step line, as flat objects of numbers and strings; `seen` is set when
// the line holds the queried body.
void rowsOfStep(const LogFields& step, const LogQuery& q, std::vector<ordered_json>& rows, bool& seen) {
  const ordered_json& events = step.array("events");
  if (q.body)
    for (size_t k = 0; step.has("bodies") && k < step.array("bodies").size(); ++k)
      seen = seen || LogFields(step.array("bodies")[k], step.where() + ": body " + std::to_string(k)).text("name") == *q.body;
  if (q.events) {
    for (size_t k = 0; k < events.size(); ++k) {
      const LogFields e(events[k], step.where() + ": event " + std::to_string(k));
      const double t = e.number("time");
      if (t < q.from || t > q.to) continue;
      std::string pairs;
      const ordered_json& list = e.array("pairs");
      for (size_t i = 0; i < list.size(); ++i) {
        const std::string text = pairText(LogFields(list[i], e.where() + ": pair " + std::to_string(i)), q.body);
        if (!text.empty()) pairs += (pairs.empty() ? "" : " ") + text;
      }
      if (q.body && pairs.empty()) continue;
      rows.push_back({{"step", step.integer("step")}, {"time", t}, {"iterations", e.integer("iterations")},
                      {"stopped_by", e.has("stopped_by") ? e.any("stopped_by") : ordered_json(nullptr)}, {"pairs", pairs}});
    }
    return;
  }
  const double t = step.number("t");
  if (t < q.from || t > q.to) return;
  ordered_json row = {{"step", step.integer("step")}, {"t", t}, {"events", events.size()}};
  long tests = 0;
  for (size_t k = 0; k < events.size(); ++k) tests += LogFields(events[k], step.where() + ": event " + std::to_string(k)).integer("iterations");
  row["toc_tests"] = tests;
  // A figure the line does not hold is shown as null, never as a made-up 0.
  auto figure = [&step](const char* key) { return step.has(key) ? step.any(key) : ordered_json(nullptr); };
  row["penetration"] = figure("penetration");
  row["energy"] = figure("energy");
  row["solver_iterations"] = figure("solver_iterations");
  row["shock_sweeps"] = figure("shock_sweeps");
  row["islands"] = step.has("island_events") ? ordered_json(step.array("island_events").size()) : ordered_json(nullptr);
  row["island_events"] = figure("island_events");
  row["sleeping"] = figure("sleeping");
  // Pairs in contact at the step's end, in a log written with --log-contacts.
  row["contacts"] = step.has("contacts") ? nlohmann::ordered_json(step.array("contacts").size()) : nlohmann::ordered_json(nullptr);
  if (q.body && step.has("bodies")) {
    for (const ordered_json& b : step.array("bodies"))
      if (b.value("name", "") == *q.body) {
        row["position"] = b.value("position", ordered_json(nullptr));
        row["velocity"] = b.value("velocity", ordered_json(nullptr));
      }
  }
  rows.push_back(row);
}

std::string cell(const ordered_json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) {
    std::ostringstream s;
    s << std::setprecision(6) << v.get<double>();
    return s.str();
  }
  if (v.is_array()) {
    std::string all;
    for (const ordered_json& x : v) all += (all.empty() ? "" : ",") + cell(x);
    return all;
  }
  return v.dump();
}

void printTable(const std::vector<ordered_json>& rows, std::ostream& out) {
  if (rows.empty()) return;
  std::vector<std::string> keys;
  for (const auto& [k, v] : rows.front().items()) keys.push_back(k);
  std::vector<size_t> width(keys.size());
  for (size_t c = 0; c < keys.size(); ++c) {
    width[c] = keys[c].size();
    for (const ordered_json& r : rows) width[c] = std::max(width[c], cell(r[keys[c]]).size());
  }
  for (size_t c = 0; c < keys.size(); ++c) out << std::left << std::setw(static_cast<int>(width[c] + 2)) << keys[c];
  out << "\n";
  for (const ordered_json& r : rows) {
    for (size_t c = 0; c < keys.size(); ++c)
      out << std::left << std::setw(static_cast<int>(width[c] + 2)) << cell(r[keys[c]]);
    out << "\n";
  }
}

}  // namespace

void inspectLog(const std::string& path, const LogQuery& query, std::ostream& out) {
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(path + ": not a file (a step log is one)");
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read it");
  std::vector<ordered_json> rows;
  std::string line;
  long steps = 0;
  bool bodySeen = false;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    if (line.empty()) continue;
    const std::string where = path + " line " + std::to_string(lineNo);
    ordered_json step;
    try {
      step = ordered_json::parse(line);
    } catch (const std::exception&) {
      // A run cut off mid-write leaves a partial last line: that one is skipped.
      if (in.eof()) break;
      throw std::runtime_error(where + ": not JSON, so not a step of a polysim step log");
    }
    rowsOfStep(LogFields(step, where), query, rows, bodySeen);
    ++steps;
  }
  if (steps == 0) throw std::runtime_error(path + ": holds no step (not a polysim step log, or empty)");
  if (query.body && !bodySeen) throw std::runtime_error(path + ": no body named \"" + *query.body + "\" in any step");
  if (query.table) printTable(rows, out);
  else out << ordered_json(rows).dump() << "\n";
}

}  // namespace polysim::sim
