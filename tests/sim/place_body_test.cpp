// World::placeBody: a body moved between steps (a pile refilled, a body respawned). What
// rested on it wakes and falls as a free body would; a place that would interpenetrate,
// or a static body, is refused and changes nothing.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim/scene.h"
#include "sim/world.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

constexpr double g = 9.81;
constexpr double kDt = 1.0 / 240;  // fine steps: the landing time is read to a step

// A ground and two unit boxes, one on the other, put to sleep. (A World is not copied:
// its database points into it.)
std::unique_ptr<World> sleepingStackOfTwo() {
  const std::string path = ::polysim::test::tempPath("stack_of_two.json");
  std::ofstream(path) << R"({"name": "stack_of_two", "bodies": [
    {"name": "ground", "static": true, "shape": {"type": "box", "size": [20, 20, 1]}, "position": [0, 0, -0.5]},
    {"name": "bottom", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 0.5]},
    {"name": "top", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 1.5]}]})";
  auto w = std::make_unique<World>(loadScene(path));
  for (int k = 0; k < 240 && !(w->asleep(1) && w->asleep(2)); ++k) w->step(kDt);
  return w;
}

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

TEST(PlaceBody, WhatRestedOnAMovedBodyWakesAndFallsAtTheFreeFallTime) {
  const std::unique_ptr<World> world = sleepingStackOfTwo();
  World& w = *world;
  ASSERT_TRUE(w.asleep(1) && w.asleep(2));
  const double energy = w.energy(), eps = w.scene().contact.tolerance;
  w.placeBody(1, at(3, 0, 0.5), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());  // out from under, same height
  EXPECT_FALSE(w.asleep(1));
  EXPECT_FALSE(w.asleep(2));
  EXPECT_NEAR(w.energy(), energy, 1e-9 * energy);
  EXPECT_TRUE(::polysim::test::near(w.bodies()[1].position, Eigen::Vector3d(3, 0, 0.5), 0.0));

  // The top box falls its own height's worth of gap (1 m, less the band it rested in).
  const double start = w.time(), drop = w.bodies()[2].position.z() - 0.5;
  double landed = -1.0;
  for (int k = 0; k < 480 && landed < 0; ++k) {
    const StepReport& r = w.step(kDt);
    if (!r.events.empty()) landed = r.events.front().time - start;
  }
  EXPECT_NEAR(landed, std::sqrt(2 * drop / g), 2 * eps / std::sqrt(2 * g * drop) + 1e-9);
  for (int k = 0; k < 480; ++k) w.step(kDt);
  EXPECT_NEAR(w.bodies()[2].position.z(), 0.5, 2 * eps);
  EXPECT_NEAR(w.bodies()[1].position.z(), 0.5, 2 * eps);  // the moved box rests where it was put
  EXPECT_NEAR(w.bodies()[1].position.x(), 3.0, 1e-9);
}

TEST(PlaceBody, ARefusedPlaceChangesNothing) {
  const std::unique_ptr<World> one = sleepingStackOfTwo(), other = sleepingStackOfTwo();
  World &w = *one, &twin = *other;
  EXPECT_THROW(w.placeBody(0, at(5, 0, 3), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(w.placeBody(2, at(0.2, 0, 0.9), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_TRUE(w.asleep(1) && w.asleep(2));
  // A body dropped later from above lands on a world that is bit for bit its twin's.
  for (World* world : {&w, &twin}) {
    world->placeBody(2, at(0, 0, 4), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    for (int k = 0; k < 240; ++k) world->step(kDt);
  }
  for (size_t i = 0; i < w.bodies().size(); ++i) {
    EXPECT_EQ(w.bodies()[i].position, twin.bodies()[i].position) << i;
    EXPECT_EQ(w.bodies()[i].velocity, twin.bodies()[i].velocity) << i;
  }
}

}  // namespace
}  // namespace polysim::sim
