// Google Benchmark for the explicit engine: one iteration = one solver step on the ring +
// rollers model of sim/solver/engine_benchmark.h. Counters: ns_per_element_cycle (and the same
// with the contact pairs). Args: elements, threads, energy terms kept (1) or skipped (0).
#include <benchmark/benchmark.h>

#include "sim/solver/engine_benchmark.h"

namespace {

void Run(benchmark::State& state, bool with_contact) {
  spallkit::sim::solver::EngineBenchmarkOptions o;
  o.elements = static_cast<int>(state.range(0));
  o.threads = static_cast<int>(state.range(1));
  o.energy_terms = state.range(2) != 0;
  auto m = spallkit::sim::solver::MakeBenchmarkModel(o, with_contact);
  for (int k = 0; k < 5; ++k) m->solver->Step();
  for (auto _ : state) m->solver->Step();
  const double cycles = static_cast<double>(state.iterations()) * m->mesh.num_elements();
  state.counters[with_contact ? "ns_per_element_cycle_with_contact" : "ns_per_element_cycle"] =
      benchmark::Counter(cycles * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["elements"] = m->mesh.num_elements();
}

void BM_FeStep(benchmark::State& state) { Run(state, false); }
void BM_FeStepWithContact(benchmark::State& state) { Run(state, true); }

BENCHMARK(BM_FeStep)
    ->ArgNames({"elements", "threads", "energy"})
    ->Args({10000, 1, 1})
    ->Args({40000, 1, 1})
    ->Args({40000, 1, 0})
    ->Args({40000, 2, 1})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FeStepWithContact)
    ->ArgNames({"elements", "threads", "energy"})
    ->Args({40000, 1, 1})
    ->Args({40000, 1, 0})
    ->Args({40000, 2, 1})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
