// Bodies tossed spinning into a corner (a floor and two walls): the hard case of one
// body meeting several static faces at once, at speed, turning, and then settling
// against them. Seeded tosses of mixed shapes (boxes of random size, hexagonal prisms,
// and the non-convex L and cup) with random spin, with and without restitution, and
// their invariants at every step: no energy gained beyond SPEC's bound (m g eps), nothing
// interpenetrating by a fresh test, nothing NaN, the body never through a wall, and at
// rest in the corner's quadrant by the end.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "collision/shapes.h"
#include "tests/sim/scenario_support.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

using test::V3;

BodySpec staticBox(const std::string& name, const V3& size, const V3& centre) {
  BodySpec b;
  b.name = name;
  b.shapeType = "box";
  b.isStatic = true;
  b.boxSize = size;
  b.mesh = collision::makeBox(size);
  b.position = centre;
  return b;
}

// The tossed body of trial `k`: its shape by turn, its size and the rest from `random`.
BodySpec tossedBody(int k, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto between = [&](double lo, double hi) { return lo + (hi - lo) * unit(random); };
  BodySpec b;
  b.name = "tossed";
  switch (k % 4) {
    case 0:
      b.shapeType = "box";
      b.boxSize = V3(between(0.2, 1.0), between(0.2, 1.0), between(0.2, 1.0));
      b.mesh = collision::makeBox(b.boxSize);
      break;
    case 1:
      b.shapeType = "mesh";
      b.mesh = ::polysim::test::makeHexPrism(between(0.2, 0.5), between(0.2, 0.8));
      break;
    case 2:
      b.shapeType = "mesh";
      b.mesh = ::polysim::test::makeL();  // 2 x 1 x 2 m, its origin at a corner
      for (Eigen::Vector3d& v : b.mesh.vertices) v *= 0.4;
      break;
    default:
      b.shapeType = "mesh";
      b.mesh = ::polysim::test::makeCup(0.4, 0.6, 0.06, 0.08);
      break;
  }
  b.mass = between(0.5, 5.0);
  const V3 axis = V3(between(-1, 1), between(-1, 1), between(-1, 1)).normalized();
  b.orientation = Eigen::AngleAxisd(between(0.0, 2 * M_PI), axis);
  b.position = V3(between(1.2, 2.0), between(1.2, 2.0), between(1.5, 2.5));
  b.velocity = V3(between(-6.0, -1.5), between(-6.0, -1.5), between(-1.0, 2.0));
  const V3 spinAxis = V3(between(-1, 1), between(-1, 1), between(-1, 1)).normalized();
  b.angularVelocity = between(3.0, 25.0) * spinAxis;
  return b;
}

TEST(TossedIntoCorner, SeededMixedShapesSettleInTheCornerWithoutGainingEnergy) {
  std::mt19937_64 random(2026);
  for (int trial = 0; trial < 24; ++trial) {
    Scene scene = test::scene("box_on_ground", false);
    scene.dt = 1.0 / 60;
    scene.contact.restitution = trial % 3 == 2 ? 0.4 : 0.0;
    // Wide enough that a rebound off the walls ends on the floor, not off its edge.
    scene.bodies = {staticBox("floor", V3(60, 60, 1), V3(25, 25, -0.5)),
                    staticBox("wall_x", V3(1, 60, 4), V3(-0.5, 25, 2)),   // its face at x = 0
                    staticBox("wall_y", V3(60, 1, 4), V3(25, -0.5, 2))};  // its face at y = 0
    scene.bodies.push_back(tossedBody(trial, random));
    const BodySpec& tossed = scene.bodies.back();
    SCOPED_TRACE("trial " + std::to_string(trial) + " (shape " + std::to_string(trial % 4) + ", restitution " +
                 std::to_string(scene.contact.restitution) + ", spin " + std::to_string(tossed.angularVelocity.norm()) +
                 " rad/s)");
    World w(scene);
    const int body = 3;
    const double mass = 1.0 / w.bodies()[body].inverseMass;
    const double bound = mass * test::g * scene.contact.tolerance;  // SPEC's energy bound
    const double initial = w.energy();
    test::FreshVerdict fresh(scene);
    double rise = 0.0, deepest = 0.0;
    int interpenetrating = 0, throughAWall = 0, wallEvents = 0;
    bool finite = true;
    test::runFor(w, 6.0, [&](const StepReport& r) {
      const dynamics::RigidBody& b = w.bodies()[body];
      finite = finite && b.position.allFinite() && b.velocity.allFinite() && b.angularVelocity.allFinite();
      rise = std::max(rise, w.energy() - initial);
      deepest = std::max(deepest, r.penetration);
      interpenetrating += fresh.interpenetrating(w);
      double lowest = 0.0;  // m, the least coordinate of a vertex: below zero, beyond a wall or the floor
      for (const Eigen::Vector3d& v : tossed.mesh.vertices) lowest = std::min(lowest, (b.pose() * v).minCoeff());
      throughAWall += lowest < -scene.contact.tolerance;
      for (const StepEvent& e : r.events)
        for (const auto& [a, c] : e.toc.crossing) wallEvents += a == 1 || a == 2 || c == 1 || c == 2;
    });
    EXPECT_TRUE(finite);
    EXPECT_LE(rise, bound) << "energy rose above the start by " << rise << " J";
    EXPECT_LE(deepest, scene.contact.tolerance);
    EXPECT_EQ(interpenetrating, 0) << "steps ending interpenetrating by a fresh test";
    EXPECT_EQ(throughAWall, 0) << "steps ending with a vertex beyond a wall or the floor";
    EXPECT_TRUE(w.atRest(body)) << "still moving at 6 s: " << w.bodies()[body].velocity.norm() << " m/s";
    EXPECT_GT(wallEvents, 0) << "the toss never struck a wall: the trial tests only a drop";
  }
}

}  // namespace
}  // namespace polysim::sim
