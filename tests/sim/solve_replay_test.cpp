// A run's contact solves, solved again on their own (World::observeSolves), end as they
// did in the run, to the bit: what the solver's benchmark (tests/bench/solver_bench.cpp)
// replays is the run's own work. It fails if a solve depends on anything its problem does
// not hold (state kept between solves, the body array's numbering, which thread swept a
// group), or if the observer reports anything but what was solved.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dynamics/settings.h"
#include "sim/world.h"
#include "tests/sim/scenario_support.h"
#include "tests/solve_replay.h"

namespace polysim::sim::test {
namespace {

// Every velocity and push velocity of a body, bit for bit.
void expectSameMotion(const dynamics::RigidBody& replayed, const dynamics::RigidBody& run, const char* what) {
  EXPECT_EQ(replayed.velocity, run.velocity) << what;
  EXPECT_EQ(replayed.angularVelocity, run.angularVelocity) << what;
  EXPECT_EQ(replayed.pushVelocity, run.pushVelocity) << what;
  EXPECT_EQ(replayed.pushAngularVelocity, run.pushAngularVelocity) << what;
}

// Seeded tilted piles (boxes) and columns of cups (not convex), through their landing:
// step-start solves and events' solves, many shared between two threads.
TEST(SolveReplay, ReplayedSolvesEndAsTheRunsDidToTheBit) {
  struct Case {
    const char* kind;
    int count;
    unsigned long long seed;
    double seconds;
  };
  int sharedSolves = 0;  // of at least kSharedSweepRows points: the sweeps share them
  for (const Case c : {Case{"pile", 27, 1, 2.0}, Case{"pile", 64, 5, 2.0}, Case{"cups", 6, 3, 2.0}}) {
    SCOPED_TRACE(std::string(c.kind) + " " + std::to_string(c.count) + " seed " + std::to_string(c.seed));
    World world(generated(c.kind, c.count, c.seed));
    int solves = 0, eventSolves = 0;
    world.observeSolves([&](const World::SolveProblem& problem, const std::vector<dynamics::RigidBody>& solved) {
      ++solves;
      eventSolves += problem.stepStart ? 0 : 1;
      sharedSolves += static_cast<int>(problem.points.size()) >= dynamics::kSharedSweepRows ? 1 : 0;
      std::vector<dynamics::RigidBody> whole, own;
      polysim::test::replay(problem, whole);
      for (size_t i = 0; i < whole.size(); ++i) expectSameMotion(whole[i], solved[i], "whole problem");
      std::vector<int> original;
      polysim::test::replay(polysim::test::compacted(problem, &original), own);
      for (size_t k = 0; k < own.size(); ++k) expectSameMotion(own[k], solved[original[k]], "compacted problem");
    });
    const long steps = std::lround(c.seconds / world.scene().dt);
    for (long s = 0; s < steps && !::testing::Test::HasFailure(); ++s) world.step(world.scene().dt);
    EXPECT_GT(solves, 60) << "too few solves to say anything";
    EXPECT_GT(eventSolves, 0);
  }
  EXPECT_GT(sharedSolves, 0);
}

// The step loop tells the solver which way is up: against gravity, whatever its direction
// (shock propagation ranks its levels along it; given none, by any contact). A seeded
// pile under gravity tilted off the pen's floor normal: every solve's problem holds the
// scene's up, -g/|g|, not +z and not zero.
TEST(SolveReplay, EverySolveIsToldWhichWayIsUp) {
  Scene scene = generated("pile", 8, 3);
  scene.gravity = Eigen::Vector3d(1.5, -1.0, -9.6);
  const Eigen::Vector3d up = -scene.gravity.normalized();
  World world(scene);
  int solves = 0;
  world.observeSolves([&](const World::SolveProblem& problem, const std::vector<dynamics::RigidBody>&) {
    ++solves;
    EXPECT_LT((problem.up - up).norm(), 1e-15) << "solve " << solves << ": up " << problem.up.transpose();
  });
  for (int s = 0; s < 120 && !::testing::Test::HasFailure(); ++s) world.step(world.scene().dt);
  EXPECT_GT(solves, 10) << "too few solves to say anything";
}

}  // namespace
}  // namespace polysim::sim::test
