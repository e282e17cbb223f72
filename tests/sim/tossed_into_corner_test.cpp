// Bodies tossed spinning into a corner (a floor and two walls): the hard case of one
// body meeting several static faces at once, at speed, turning, and then settling
// against them. Seeded tosses of mixed shapes (boxes of random size, hexagonal prisms,
// and the non-convex L and cup) with random spin, with and without restitution, and
// their invariants at every step: no energy gained beyond SPEC's bound (m g eps), nothing
// interpenetrating by a fresh test, nothing NaN, the body never through a wall, and at
// rest in the corner's quadrant by the end.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/sim/scenario_support.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

using test::V3;

BodySpec staticBox(const std::string& name, const V3& size, const V3& centre) {
  BodySpec b;
  b.name = name;
  b.isStatic = true;
  test::setBoxSize(b, size);
  b.position = centre;
  return b;
}

// The tossed body of trial `k`: its shape by turn, the rest drawn. It starts 1.4 to
// 1.8 m from each wall (clear of both: no shape reaches 1.2 m from its origin), 2 to 3 m
// up, and moves towards both walls at 3 to 6 m/s: its centre would reach a wall's plane
// within 0.6 s, about when it first lands, and friction (0.5 g) takes 0.6 s or more to
// stop it.
BodySpec tossedBody(int k, ::polysim::test::SeededDraws& draw) {
  BodySpec b;
  b.name = "tossed";
  switch (k % 4) {
    case 0:
      test::setBoxSize(b, draw.vector(0.2, 1.0));
      break;
    case 1: {
      b.shapeType = "mesh";
      const double radius = draw.between(0.2, 0.5);
      b.mesh = ::polysim::test::makeHexPrism(radius, draw.between(0.2, 0.8));
      break;
    }
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
  b.mass = draw.between(0.5, 5.0);
  const V3 axis = draw.direction();
  b.orientation = Eigen::AngleAxisd(draw.between(0.0, 2 * M_PI), axis);
  b.position = draw.vector(V3(1.4, 1.4, 2.0), V3(1.8, 1.8, 3.0));
  b.velocity = draw.vector(V3(-6.0, -6.0, -1.0), V3(-3.0, -3.0, 2.0));
  const V3 spinAxis = draw.direction();
  b.angularVelocity = draw.between(3.0, 25.0) * spinAxis;
  return b;
}

// Trial `k`'s scene: the floor and two walls, then the tossed body (body 3), drawn next
// from `draw`; restitution 0.4 every third trial, else 0.
Scene tossScene(::polysim::test::SeededDraws& draw, int k) {
  Scene scene = test::scene("box_on_ground", false);
  scene.dt = 1.0 / 60;
  scene.contact.restitution = k % 3 == 2 ? 0.4 : 0.0;
  // Wide enough that a rebound off the walls ends on the floor, not off its edge.
  scene.bodies = {staticBox("floor", V3(60, 60, 1), V3(25, 25, -0.5)),
                  staticBox("wall_x", V3(1, 60, 4), V3(-0.5, 25, 2)),   // its face at x = 0
                  staticBox("wall_y", V3(60, 1, 4), V3(25, -0.5, 2))};  // its face at y = 0
  scene.bodies.push_back(tossedBody(k, draw));
  return scene;
}

constexpr int kTossed = 3;  // the tossed body's index

// What a toss kept true, step by step.
struct Toss {
  double rise = 0.0;     // J, largest rise of the energy over its start
  double bound = 0.0;    // J, SPEC's energy bound for the body: m g eps
  double deepest = 0.0;  // m, deepest overlap of a committed state
  int interpenetrating = 0;  // steps ending interpenetrating by a fresh test
  int throughAWall = 0;      // steps ending with a vertex beyond a wall or the floor
  int wallEvents = 0;        // events whose crossing pairs hold a wall
  int eventsLastSecond = 0;
  bool finite = true;
  bool atRest = false;       // at the end
  double speed = 0.0;        // m/s, at the end
};

Toss runToss(const Scene& scene, double seconds) {
  World w(scene);
  const BodySpec& tossed = scene.bodies[kTossed];
  Toss t;
  t.bound = test::g * scene.contact.tolerance / w.bodies()[kTossed].inverseMass;
  const double initial = w.energy();
  test::FreshVerdict fresh(scene);
  test::runFor(w, seconds, [&](const StepReport& r) {
    const dynamics::RigidBody& b = w.bodies()[kTossed];
    t.finite = t.finite && b.position.allFinite() && b.velocity.allFinite() && b.angularVelocity.allFinite();
    t.rise = std::max(t.rise, w.energy() - initial);
    t.deepest = std::max(t.deepest, r.penetration);
    t.interpenetrating += fresh.interpenetrating(w);
    double lowest = 0.0;  // m, the least coordinate of a vertex: below zero, beyond a wall or the floor
    for (const Eigen::Vector3d& v : tossed.mesh.vertices) lowest = std::min(lowest, (b.pose() * v).minCoeff());
    t.throughAWall += lowest < -scene.contact.tolerance;
    for (const StepEvent& e : r.events)
      for (const auto& [a, c] : e.toc.crossing) t.wallEvents += a == 1 || a == 2 || c == 1 || c == 2;
    if (w.time() > seconds - 1.0) t.eventsLastSecond += static_cast<int>(r.events.size());
  });
  t.atRest = w.atRest(kTossed);
  t.speed = w.bodies()[kTossed].velocity.norm();
  return t;
}

void expectInvariants(const Toss& t, double tolerance) {
  EXPECT_TRUE(t.finite);
  EXPECT_LE(t.rise, t.bound) << "energy rose above the start by " << t.rise << " J";
  EXPECT_LE(t.deepest, tolerance);
  EXPECT_EQ(t.interpenetrating, 0) << "steps ending interpenetrating by a fresh test";
  EXPECT_EQ(t.throughAWall, 0) << "steps ending with a vertex beyond a wall or the floor";
}

TEST(TossedIntoCorner, SeededMixedShapesSettleInTheCornerWithoutGainingEnergy) {
  ::polysim::test::SeededDraws draw(2026);
  for (int trial = 0; trial < 24; ++trial) {
    const Scene scene = tossScene(draw, trial);
    const BodySpec& tossed = scene.bodies[kTossed];
    SCOPED_TRACE("trial " + std::to_string(trial) + " (shape " + std::to_string(trial % 4) + ", restitution " +
                 std::to_string(scene.contact.restitution) + ", spin " + std::to_string(tossed.angularVelocity.norm()) +
                 " rad/s)");
    const Toss t = runToss(scene, 6.0);
    expectInvariants(t, scene.contact.tolerance);
    EXPECT_TRUE(t.atRest) << "still moving at 6 s: " << t.speed << " m/s";
    EXPECT_GT(t.wallEvents, 0) << "the toss never struck a wall: the trial tests only a drop";
  }
}

// Draws 31337, trial 3: a cup tossed at 23 rad/s ends on its side by 2 s. While a cup
// did not speculate (it is not convex), it rocked there for good in a cycle two steps
// long: each step began with its side on the floor along one edge only, the other lifted
// past the wide band by the event before; the step's solve, holding all its gravity on
// that edge, tipped the cup onto the other at 0.11 rad/s, and the impact kept a quarter
// of the spin and lifted the first edge out of the band again (1.76 cm/s at every step's
// end, one event a step, the energy the same to 1e-6 J). Speculating against the floor,
// the cup holds both edges from the step's start and rests.
TEST(TossedIntoCorner, ACupTossedOntoItsSideComesToRest) {
  ::polysim::test::SeededDraws draw(31337);
  for (int k = 0; k < 3; ++k) tossScene(draw, k);  // the draws of the trials before
  const Scene scene = tossScene(draw, 3);
  const Toss t = runToss(scene, 10.0);
  expectInvariants(t, scene.contact.tolerance);
  EXPECT_TRUE(t.atRest) << "moving at " << t.speed << " m/s";
  EXPECT_EQ(t.eventsLastSecond, 0);
}

}  // namespace
}  // namespace polysim::sim
