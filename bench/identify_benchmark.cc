// Identification cost per record (docs/IDENTIFY.md, docs/PERFORMANCE.md): diagnosis excluded, one
// thread, 1 s synthetic records of an N205EM at 1200 rpm (10 dB) with one, two (adjacent) and three
// spalled rollers. The budget is 5 s of CPU per 1 s record.
//   build/bench/identify_benchmark --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include "core/bearing.h"
#include "dsp/diagnose.h"
#include "identify/identify.h"
#include "identify/synthetic_record.h"

namespace {

using namespace spallkit;

struct Case {
  Record record;
  dsp::Diagnosis diagnosis;
};

Case MakeCase(const std::vector<std::pair<int, double>>& slots_phases) {
  identify::SyntheticRecordSpec s;
  s.snr_db = 10.0;
  for (auto [slot, phase] : slots_phases) {
    identify::SyntheticRoller r;
    r.slot = slot;
    r.spin_phase_rad = phase;
    s.rollers.push_back(r);
  }
  Case c;
  c.record = identify::MakeSyntheticRecord(s);
  dsp::DiagnoseOptions o;
  o.threads = 1;
  c.diagnosis = dsp::Diagnose(c.record, CatalogBearing("N205EM"), 20.0, o);
  return c;
}

void Run(benchmark::State& state, const Case& c) {
  identify::IdentifyOptions o;
  o.radial_load_n = 10000.0;
  const BearingGeometry g = CatalogBearing("N205EM");
  int count = -1;
  for (auto _ : state) {
    const identify::Identification id = identify::Identify(c.record, g, 20.0, c.diagnosis, o);
    count = id.count_identifiable ? id.count : -1;
    benchmark::DoNotOptimize(count);
  }
  state.counters["count"] = count;
  state.counters["ms_per_s_of_record"] = benchmark::Counter(
      1e3 * c.record.duration_s(),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_IdentifyOneRoller(benchmark::State& state) {
  static const Case c = MakeCase({{0, 0.0}});
  Run(state, c);
}
void BM_IdentifyAdjacentRollers(benchmark::State& state) {
  static const Case c = MakeCase({{0, 0.0}, {1, 2.09}});
  Run(state, c);
}
void BM_IdentifyThreeRollers(benchmark::State& state) {
  static const Case c = MakeCase({{0, 0.0}, {3, 1.05}, {7, 3.49}});
  Run(state, c);
}

BENCHMARK(BM_IdentifyOneRoller)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK(BM_IdentifyAdjacentRollers)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK(BM_IdentifyThreeRollers)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

}  // namespace

BENCHMARK_MAIN();
