#include "dynamics/sleep.h"

namespace polysim::dynamics {

double slowTimeAfterStep(const RigidBody& body, double size, double dt, double slowFor, const SleepSettings& settings) {
  if (body.isStatic) return slowFor + dt;
  const bool slow = body.velocity.norm() < settings.speed && body.angularVelocity.norm() * size < settings.speed;
  return slow ? slowFor + dt : 0.0;
}

}  // namespace polysim::dynamics
