#include "sim/log_inspect.h"

#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace polysim::sim {
namespace {

using nlohmann::ordered_json;

bool touches(const ordered_json& pair, const std::string& body) { return pair["a"] == body || pair["b"] == body; }

// The rows for one step line, as flat objects of numbers and strings.
void rowsOfStep(const ordered_json& step, const LogQuery& q, std::vector<ordered_json>& rows) {
  if (q.events) {
    for (const ordered_json& e : step["events"]) {
      const double t = e["time"].get<double>();
      if (t < q.from || t > q.to) continue;
      std::string pairs;
      for (const ordered_json& p : e["pairs"]) {
        if (q.body && !touches(p, *q.body)) continue;
        std::string kinds;
        for (const ordered_json& c : p["contacts"]) kinds += (kinds.empty() ? "" : "+") + c["type"].get<std::string>();
        pairs += (pairs.empty() ? "" : " ") + p["a"].get<std::string>() + "/" + p["b"].get<std::string>() + ":" +
                 (kinds.empty() ? p["status"].get<std::string>() : kinds);
      }
      if (q.body && pairs.empty()) continue;
      rows.push_back({{"step", step["step"]}, {"time", t}, {"iterations", e["iterations"]},
                      {"stopped_by", e["stopped_by"]}, {"pairs", pairs}});
    }
    return;
  }
  const double t = step["t"].get<double>();
  if (t < q.from || t > q.to) return;
  ordered_json row = {{"step", step["step"]}, {"t", t}, {"events", step["events"].size()}};
  int tests = 0;
  for (const ordered_json& e : step["events"]) tests += e["iterations"].get<int>();
  row["toc_tests"] = tests;
  // A figure the line does not hold is shown as null, never as a made-up 0.
  auto figure = [&step](const char* key) { return step.contains(key) ? step[key] : ordered_json(nullptr); };
  row["penetration"] = figure("penetration");
  row["energy"] = figure("energy");
  row["solver_iterations"] = figure("solver_iterations");
  row["islands"] = step.contains("island_events") ? ordered_json(step["island_events"].size()) : ordered_json(nullptr);
  row["island_events"] = figure("island_events");
  if (q.body) {
    for (const ordered_json& b : step["bodies"])
      if (b["name"] == *q.body) {
        row["position"] = b["position"];
        row["velocity"] = b["velocity"];
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
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<ordered_json> rows;
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    if (line.empty()) continue;
    ordered_json step;
    try {
      step = ordered_json::parse(line);
      if (!step.contains("step") || !step.contains("t") || !step.contains("events")) throw std::runtime_error("");
    } catch (const std::exception&) {
      // A run cut off mid-write leaves a partial last line: that one is skipped.
      if (in.peek() == EOF) break;
      throw std::runtime_error(path + " line " + std::to_string(lineNo) + ": not a step of a polysim step log");
    }
    rowsOfStep(step, query, rows);
  }
  if (query.table) printTable(rows, out);
  else out << ordered_json(rows).dump() << "\n";
}

}  // namespace polysim::sim
