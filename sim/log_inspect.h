#pragma once
// `polysim log`: a step log read back as a per-step or per-event table, so that a run can
// be inspected without writing code.

#include <iosfwd>
#include <optional>
#include <string>

namespace polysim::sim {

struct LogQuery {
  std::optional<std::string> body;  // only events touching this body; its state per step
  double from = -1e300, to = 1e300;  // s: the steps (or events) with t in [from, to]
  bool events = false;              // one row per contact event instead of per step
  bool table = false;               // aligned text instead of JSON
};

/// Reads the JSON Lines log at `path` and writes the rows. A last line cut short (no
/// newline, not JSON: a run killed mid-write) is skipped. Throws std::runtime_error naming
/// the file, the line and the field (e.g. "line 3: event 0: pair 1: no \"a\"") for a line
/// that is not a step as the step log writes it; naming the file when it is not a
/// regular file or holds no step; naming the body when `body` is in no step.
void inspectLog(const std::string& path, const LogQuery& query, std::ostream& out);

}  // namespace polysim::sim
