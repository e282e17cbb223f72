#pragma once
// The step log: JSON Lines, one object per step, flushed as the run goes so that an
// interrupted run leaves every finished step readable.

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/engine.h"
#include "sim/world.h"

namespace polysim::sim {

/// One step as a log line: step, t, events (time, iterations, stopped_by, pairs with
/// contacts), event_limit, island_bodies, island_events, sleeping (bodies asleep at the
/// step's end), fell_asleep and woke (names, only when some did), bodies (name,
/// position, orientation, velocity, angular_velocity), energy, penetration,
/// solver_iterations. With `withContacts`, also contacts: the pairs in contact at the
/// step's end, as `pairs` are written (polysim view draws them).
nlohmann::ordered_json stepToJson(const World& world, const StepReport& report, bool withContacts = false);

/// Another engine's step (ODE's, for `polysim compare --log-dir`) as a step log line:
/// step, t, events (none: it has no events), bodies, energy, penetration.
nlohmann::ordered_json engineStepToJson(const Engine& engine, long step, double time);

class StepLog {
 public:
  /// Opens (truncates) `path`; throws std::runtime_error naming it when it cannot.
  /// `withContacts`: see stepToJson.
  explicit StepLog(const std::string& path, bool withContacts = false);
  /// Appends the step's line and flushes it; throws std::runtime_error naming the file
  /// when it cannot be written (a full disk, /dev/full). The first line also names the
  /// scene file (`scene`, an absolute path), for `polysim view`.
  void write(const World& world, const StepReport& report);
  /// The same for a line made elsewhere (engineStepToJson); `sceneFile` as above.
  void write(nlohmann::ordered_json line, const std::string& sceneFile);

 private:
  std::string path_;
  std::ofstream out_;
  bool withContacts_ = false;
  bool first_ = true;
};

}  // namespace polysim::sim
