// Wall time per step of the step loop (issue 5): the drop scene and the 10- and 20-box
// stacks at dt 1/60, measured after the scene has settled for a second. Per simulated
// second = per step x steps per second (reported as a counter). Run:
//   build/tests/bench/step_bench --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "sim/world.h"

namespace polysim::bench {
namespace {

void BM_Step(benchmark::State& state, const std::string& name) {
  sim::Scene scene = sim::loadScene(std::string(POLYSIM_SCENES_DIR) + "/" + name + ".json");
  scene.sleep.enabled = false;  // the awake step's cost; sleep_bench measures sleeping
  sim::World world(scene);
  for (int k = 0; k < std::lround(1.0 / scene.dt); ++k) world.step(scene.dt);  // settle
  long events = 0, steps = 0;
  for (auto _ : state) {
    events += static_cast<long>(world.step(scene.dt).events.size());
    ++steps;
  }
  state.counters["bodies"] = static_cast<double>(scene.bodies.size());
  state.counters["steps_per_sim_s"] = 1.0 / scene.dt;
  state.counters["events_per_step"] = static_cast<double>(events) / steps;
}

BENCHMARK_CAPTURE(BM_Step, drop_box, std::string("drop_box"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Step, stack_10, std::string("stack_10"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Step, stack_20, std::string("stack_20"))->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace polysim::bench
