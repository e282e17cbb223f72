#pragma once
// What the scenario tests share: the scenes in scenes/ by name, bodies by name, and a
// run for so many seconds.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sim/scene.h"
#include "sim/world.h"

namespace polysim::sim::test {

using V3 = Eigen::Vector3d;
inline constexpr double g = 9.81;  // m/s^2, the scenes' gravity

// The scene in scenes/; `sleeping` false keeps every body awake (a test of the solver).
inline Scene scene(const std::string& name, bool sleeping = true) {
  Scene s = loadScene(std::string(POLYSIM_SCENES_DIR) + "/" + name + ".json");
  s.sleep.enabled = sleeping;
  return s;
}

inline int bodyIndex(const World& w, const std::string& name) {
  for (size_t i = 0; i < w.scene().bodies.size(); ++i)
    if (w.scene().bodies[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no body " << name;
  return 0;
}

// Runs the world for `seconds`, calling f after each step.
template <class F>
void runFor(World& w, double seconds, F&& f) {
  const long steps = std::lround(seconds / w.scene().dt);
  for (long k = 0; k < steps; ++k) f(w.step(w.scene().dt));
}

}  // namespace polysim::sim::test
