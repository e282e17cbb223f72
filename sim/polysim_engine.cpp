#include "sim/polysim_engine.h"

namespace polysim::sim {

std::vector<BodyState> PolysimEngine::bodyStates() const {
  std::vector<BodyState> states;
  for (size_t i = 0; i < world_.bodies().size(); ++i) {
    const dynamics::RigidBody& b = world_.bodies()[i];
    if (b.isStatic) continue;
    states.push_back({world_.scene().bodies[i].name, b.position, b.orientation, b.velocity, b.angularVelocity,
                      world_.atRest(static_cast<int>(i))});
  }
  return states;
}

std::optional<double> PolysimEngine::firstContactTime() const {
  if (world_.firstContactTime() < 0) return std::nullopt;
  return world_.firstContactTime();
}

int PolysimEngine::sleepingBodies() const {
  int sleeping = 0;
  for (size_t i = 0; i < world_.bodies().size(); ++i) sleeping += world_.asleep(static_cast<int>(i));
  return sleeping;
}

}  // namespace polysim::sim
