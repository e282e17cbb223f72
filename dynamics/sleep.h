#pragma once
// Sleeping: an island whose bodies have all been slow for a while stops costing anything
// until something touches it (as in Box2D, Jolt and Bullet). The rule for one body lives
// here; which bodies make an island, and when a sleeping one wakes, is the step loop's.

#include "dynamics/rigid_body.h"
#include "dynamics/settings.h"

namespace polysim::dynamics {

struct SleepSettings {
  bool enabled = true;
  double speed = kSleepSpeed;  // m/s: the body and the farthest point of its spin stay below it
  double time = kTimeToSleep;  // s: for this long before its island may sleep
};

/// How long (s) `body` has been slow after a step of `dt` seconds: `slowFor + dt` when its
/// centre of mass and its spin at `size` (m, its farthest point from the centre of mass)
/// are both slower than `settings.speed`, else 0. A static body is always slow.
double slowTimeAfterStep(const RigidBody& body, double size, double dt, double slowFor, const SleepSettings& settings);

}  // namespace polysim::dynamics
