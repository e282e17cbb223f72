#pragma once
// The step log: JSON Lines, one object per step, flushed as the run goes so that an
// interrupted run leaves every finished step readable.

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/world.h"

namespace polysim::sim {

/// One step as a log line: step, t, events (time, iterations, stopped_by, pairs with
/// contacts), event_limit, island_bodies, island_events, sleeping (bodies asleep at the
/// step's end), fell_asleep and woke (names, only when some did), bodies (name,
/// position, orientation, velocity, angular_velocity), energy, penetration,
/// solver_iterations.
nlohmann::ordered_json stepToJson(const World& world, const StepReport& report);

class StepLog {
 public:
  /// Opens (truncates) `path`; throws std::runtime_error naming it when it cannot.
  explicit StepLog(const std::string& path);
  /// Appends the step's line and flushes it; throws std::runtime_error naming the file
  /// when it cannot be written (a full disk, /dev/full).
  void write(const World& world, const StepReport& report);

 private:
  std::string path_;
  std::ofstream out_;
};

}  // namespace polysim::sim
