// The contact solver alone, on the problems a run gave it (issue 16). A pile of boxes is
// stepped to its landing; the solves of the next steps are kept (World::observeSolves)
// and solved again, each from its own copy, in every iteration. The same problems every
// time: a change to the solver shows in its work to the last sweep, without the chaos of
// a whole run, where one bit of difference sends the pile elsewhere. Run:
//   build/tests/bench/solver_bench --benchmark_counters_tabular=true
// Arguments: boxes in the pile, its seed, and the step the capture starts at (60 steps a
// second). Counters, over one replay of every kept solve: solves, points (contact points
// per solve, mean), row_solves (the sweeps' work, points solved summed over sweeps, in
// millions), shock_rows (shock propagation's, likewise), unconverged (share of solves whose
// sweeps stopped at a limit), ms (the process's CPU per replay, every thread's).

#include <benchmark/benchmark.h>

#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "dynamics/contact_solver.h"
#include "sim/run_record.h"
#include "sim/scene_generators.h"
#include "sim/world.h"
#include "tests/solve_replay.h"

namespace polysim::bench {
namespace {

constexpr int kCapturedSteps = 30;  // half a second of the landing
constexpr double kMsPerS = 1e3;
constexpr double kMillion = 1e6;

// `polysim make pile --count N --seed S`, read as a scene file would be.
sim::Scene pile(int count, int seed) {
  sim::MakeOptions o;
  o.kind = "pile";
  o.count = count;
  o.seed = static_cast<unsigned long long>(seed);
  std::istringstream text(sim::makeScene(o).dump());
  return sim::readScene(text, "pile" + std::to_string(count) + "_seed" + std::to_string(seed) + ".json");
}

// The solves of kCapturedSteps steps from `startStep` on, kept once per argument set.
const std::vector<sim::World::SolveProblem>& captured(int count, int seed, int startStep) {
  static std::map<std::tuple<int, int, int>, std::vector<sim::World::SolveProblem>> kept;
  const auto key = std::make_tuple(count, seed, startStep);
  if (const auto at = kept.find(key); at != kept.end()) return at->second;
  std::vector<sim::World::SolveProblem>& problems = kept[key];
  const sim::Scene scene = pile(count, seed);
  sim::World world(scene);
  for (int s = 0; s < startStep; ++s) world.step(scene.dt);
  world.observeSolves([&problems](const sim::World::SolveProblem& p, const std::vector<dynamics::RigidBody>&) {
    problems.push_back(test::compacted(p));
  });
  for (int s = 0; s < kCapturedSteps; ++s) world.step(scene.dt);
  return problems;
}

void BM_ReplaySolves(benchmark::State& state) {
  const std::vector<sim::World::SolveProblem>& problems =
      captured(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  long points = 0, rowSolves = 0, shockRows = 0, unconverged = 0;
  double cpu = 0.0;
  for (auto _ : state) {
    points = rowSolves = shockRows = unconverged = 0;
    const double start = sim::processCpuSeconds();
    std::vector<dynamics::RigidBody> bodies;
    for (const sim::World::SolveProblem& p : problems) {
      const dynamics::SolveStats stats = test::replay(p, bodies);
      points += static_cast<long>(p.points.size());
      rowSolves += stats.rowSolves;
      shockRows += stats.shockRowSolves;
      unconverged += stats.converged ? 0 : 1;
    }
    cpu = sim::processCpuSeconds() - start;
  }
  const double solves = static_cast<double>(problems.size());
  state.counters["solves"] = solves;
  state.counters["points"] = solves > 0 ? static_cast<double>(points) / solves : 0.0;
  state.counters["row_solves"] = static_cast<double>(rowSolves) / kMillion;
  state.counters["shock_rows"] = static_cast<double>(shockRows) / kMillion;
  state.counters["unconverged"] = solves > 0 ? static_cast<double>(unconverged) / solves : 0.0;
  state.counters["ms"] = cpu * kMsPerS;
}

// Piles of 343 at their landing (1.5 s) and as they settle (2.5 s), and of 1000 landing;
// the pile of 64 is the smoke test's (tests/bench/CMakeLists.txt).
BENCHMARK(BM_ReplaySolves)
    ->Args({64, 1, 60})
    ->Args({343, 1, 90})
    ->Args({343, 2, 90})
    ->Args({343, 1, 150})
    ->Args({1000, 1, 90})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace polysim::bench
