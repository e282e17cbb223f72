// The benchmarks' main: Google Benchmark's own, after the heap policy polysim's main sets
// (sim/heap_policy.h), so that both engines are timed as the program runs them.

#include <benchmark/benchmark.h>

#include "sim/heap_policy.h"

int main(int argc, char** argv) {
  polysim::sim::keepFreedMemory();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
