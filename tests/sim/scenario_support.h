#pragma once
// What the scenario tests share: the scenes in scenes/ by name, bodies by name, and a
// run for so many seconds.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <string>

#include "collision/intersection.h"
#include "collision/shapes.h"
#include "sim/scene.h"
#include "sim/scene_generators.h"
#include "sim/world.h"
#include "tests/test_support.h"

namespace polysim::sim::test {

using V3 = Eigen::Vector3d;
inline constexpr double g = 9.81;  // m/s^2, the scenes' gravity

// The scene in scenes/; `sleeping` false keeps every body awake (a test of the solver).
inline Scene scene(const std::string& name, bool sleeping = true) {
  Scene s = loadScene(std::string(POLYSIM_SCENES_DIR) + "/" + name + ".json");
  s.sleep.enabled = sleeping;
  return s;
}

// Makes `body` a box of `size` (m), as a scene file's "box" shape does.
inline void setBoxSize(BodySpec& body, const V3& size) {
  body.shapeType = "box";
  body.boxSize = size;
  body.mesh = collision::makeBox(size);
}

// The scene `polysim make KIND --count N --seed S [--tilt T]` writes, read back as a
// scene file is, with sleeping off: a busy scene's tests guard the contact solver, and
// "at rest" must come from it, not from bodies put to sleep at 1 cm/s.
inline Scene generated(const std::string& kind, int count, unsigned long long seed = 1, std::optional<double> tilt = {}) {
  MakeOptions o;
  o.kind = kind;
  o.count = count;
  o.seed = seed;
  o.tilt = tilt;
  const std::string path = ::polysim::test::tempPath("generated_" + kind + ".json");
  std::ofstream(path) << makeScene(o).dump(1) << "\n";
  Scene s = loadScene(path);
  s.sleep.enabled = false;
  return s;
}

inline int bodyIndex(const World& w, const std::string& name) {
  for (size_t i = 0; i < w.scene().bodies.size(); ++i)
    if (w.scene().bodies[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no body " << name;
  return 0;
}

// A fresh test4Intersection() of the world at its current poses, with no contact reuse
// and no state kept between calls: whether a committed state interpenetrates, judged
// without trusting what the step loop reported or kept.
class FreshVerdict {
 public:
  explicit FreshVerdict(const Scene& scene) : db_(buildObjectDatabase(scene)) {}
  bool interpenetrating(const World& w) {
    for (size_t i = 0; i < db_.objects.size(); ++i) db_.objects[i].X_WO = w.bodies()[i].pose();
    collision::IntersectionOptions verdictOnly;
    verdictOnly.contacts = false;
    verdictOnly.stopAtInterpenetration = true;
    return collision::test4Intersection(db_, verdictOnly).status == collision::Status::Interpenetrating;
  }

 private:
  collision::ObjectDatabase db_;
};

// Runs the world for `seconds`, calling f after each step.
template <class F>
void runFor(World& w, double seconds, F&& f) {
  const long steps = std::lround(seconds / w.scene().dt);
  for (long k = 0; k < steps; ++k) f(w.step(w.scene().dt));
}

}  // namespace polysim::sim::test
