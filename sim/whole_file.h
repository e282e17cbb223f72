#pragma once
// Output files written whole or not at all: an interrupted or failed write leaves no
// half-written file for a script to pick up.

#include <functional>
#include <iosfwd>
#include <string>

namespace polysim::sim {

/// Writes `path` through `write`: into `path`.partial, renamed to `path` once complete.
/// The partial file is opened before `write` runs, so an unwritable path fails at once.
/// Throws std::runtime_error naming the file and `what` it holds when it cannot be
/// written; whatever `write` throws passes through. Either way nothing is left behind.
void writeWholeFile(const std::string& path, const std::string& what, const std::function<void(std::ostream&)>& write);

}  // namespace polysim::sim
