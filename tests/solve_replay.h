#pragma once
// Solving a run's contact solves again on their own (sim::World::observeSolves): shared by
// the solver's benchmark (tests/bench/solver_bench.cpp) and the test that a replay
// reproduces the run (tests/sim/solve_replay_test.cpp).

#include <map>
#include <vector>

#include "dynamics/contact_solver.h"
#include "sim/world.h"

namespace polysim::test {

/// The problem with only the bodies its points name, renumbered in the order first named;
/// `original`, when given, receives each kept body's index in the whole problem. A pile's
/// solve names a few hundred of its thousand bodies, and a replay copies them every time.
/// The solver's result does not depend on the numbering (solve_replay_test.cpp checks it).
inline sim::World::SolveProblem compacted(const sim::World::SolveProblem& whole, std::vector<int>* original = nullptr) {
  sim::World::SolveProblem own = whole;
  own.bodies.clear();
  std::map<int, int> renumbered;
  const auto body = [&](int i) {
    const auto [at, fresh] = renumbered.try_emplace(i, static_cast<int>(own.bodies.size()));
    if (fresh) {
      own.bodies.push_back(whole.bodies[i]);
      if (original) original->push_back(i);
    }
    return at->second;
  };
  for (dynamics::ContactPoint& p : own.points) p.a = body(p.a), p.b = body(p.b);
  return own;
}

/// Solves the problem again from its own copy; `bodies` receives the bodies as it left them.
inline dynamics::SolveStats replay(const sim::World::SolveProblem& p, std::vector<dynamics::RigidBody>& bodies) {
  bodies = p.bodies;
  std::vector<dynamics::ContactPoint> points = p.points;
  return dynamics::solveContacts(bodies, points, p.horizon, p.allowedOverlap, p.maxSweeps, p.up);
}

}  // namespace polysim::test
