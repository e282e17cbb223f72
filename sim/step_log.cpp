#include "sim/step_log.h"

#include <filesystem>
#include <stdexcept>

#include "sim/json_output.h"

namespace polysim::sim {

nlohmann::ordered_json stepToJson(const World& world, const StepReport& report, bool withContacts) {
  std::vector<std::string> names;
  for (const BodySpec& b : world.scene().bodies) names.push_back(b.name);
  nlohmann::ordered_json events = nlohmann::ordered_json::array();
  for (const StepEvent& e : report.events)
    events.push_back({{"time", forOutput(e.time)},
                      {"iterations", e.toc.iterations},
                      {"stopped_by", collision::toString(e.toc.stoppedBy)},
                      {"crossing", crossingToJson(e.toc.crossing, names)},
                      {"pairs", pairsToJson(e.toc.pairs, names)}});
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (size_t i = 0; i < world.bodies().size(); ++i) {
    const dynamics::RigidBody& b = world.bodies()[i];
    if (b.isStatic) continue;
    bodies.push_back(bodyStateToJson(names[i], b.position, b.orientation, b.velocity, b.angularVelocity));
  }
  nlohmann::ordered_json line;
  line["step"] = report.step;
  line["t"] = forOutput(report.time);
  line["events"] = events;
  if (report.eventLimitHit) line["event_limit"] = true;
  if (report.islandsJoined > 0) line["islands_joined"] = report.islandsJoined;
  nlohmann::ordered_json islandBodies = nlohmann::ordered_json::array(), islandEvents = nlohmann::ordered_json::array();
  for (const IslandReport& island : report.islands) {
    islandBodies.push_back(island.bodies);
    islandEvents.push_back(island.events);
  }
  line["island_bodies"] = islandBodies;
  line["island_events"] = islandEvents;
  line["sleeping"] = report.sleeping;
  auto named = [&names](const std::vector<int>& bodyIndices) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (int i : bodyIndices) list.push_back(names[i]);
    return list;
  };
  if (!report.fellAsleep.empty()) line["fell_asleep"] = named(report.fellAsleep);
  if (!report.woke.empty()) line["woke"] = named(report.woke);
  line["bodies"] = bodies;
  line["energy"] = forOutput(world.energy());
  line["penetration"] = forOutput(report.penetration);
  line["solver_iterations"] = report.solverIterations;
  line["shock_sweeps"] = report.shockSweeps;
  if (withContacts) line["contacts"] = pairsToJson(world.contacts(), names);
  return line;
}

nlohmann::ordered_json engineStepToJson(const Engine& engine, long step, double time) {
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (const BodyState& b : engine.bodyStates())
    bodies.push_back(bodyStateToJson(b.name, b.position, b.orientation, b.velocity, b.angularVelocity));
  nlohmann::ordered_json line;
  line["step"] = step;
  line["t"] = forOutput(time);
  line["events"] = nlohmann::ordered_json::array();
  line["bodies"] = bodies;
  line["energy"] = forOutput(engine.energy());
  line["penetration"] = forOutput(engine.stepPenetration());
  return line;
}

StepLog::StepLog(const std::string& path, bool withContacts)
    : path_(path), out_(path, std::ios::trunc), withContacts_(withContacts) {
  if (!out_) throw std::runtime_error(path + ": cannot write the step log");
}

void StepLog::write(const World& world, const StepReport& report) {
  write(stepToJson(world, report, withContacts_), world.scene().file);
}

void StepLog::write(nlohmann::ordered_json line, const std::string& sceneFile) {
  if (first_) line["scene"] = std::filesystem::absolute(sceneFile).string();
  first_ = false;
  // The line and its end in one write, flushed: a run killed between steps leaves only
  // whole lines, and one killed inside a write leaves a last line without its end, which
  // readers know as cut short.
  const std::string text = line.dump() + "\n";
  out_.write(text.data(), static_cast<std::streamsize>(text.size()));
  out_.flush();
  if (!out_) throw std::runtime_error(path_ + ": writing the step log failed");
}

}  // namespace polysim::sim
