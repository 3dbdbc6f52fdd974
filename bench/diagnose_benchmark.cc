// The whole `spall diagnose` analysis (kurtogram + candidate-band SES + fault-band detection; no
// I/O, no plots) on 10 s at 48 kHz of a synthetic outer-race record (6205 at 1797 rpm).
// Run: build-diagnose/bench/diagnose_benchmark --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include "core/bearing.h"
#include "dsp/diagnose.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace {

spallkit::dsp::Record MakeRecord() {
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = 48000;
  s.duration_s = 10.0;
  s.rate_hz = 107.36 * 0.99;
  s.resonance_hz = 12000;
  s.amplitude = 3.0;
  s.noise_rms = 0.4;
  s.shaft_hz = 29.95;
  s.shaft_amplitude = 0.5;
  s.mains_amplitude = 0.2;
  spallkit::dsp::Record r;
  r.samples = spallkit::testing::MakeFaultSignal(s);
  r.sample_rate_hz = s.fs_hz;
  return r;
}

void BM_Diagnose10s48k(benchmark::State& state) {
  const auto record = MakeRecord();
  const auto bearing = spallkit::CatalogBearing("6205");
  std::string verdict;
  int bands = 0;
  for (auto _ : state) {
    const auto d = spallkit::dsp::Diagnose(record, bearing, 1797 / 60.0);
    verdict = d.verdict;
    bands = d.candidate_bands;
    benchmark::DoNotOptimize(d.faults.data());
  }
  state.SetLabel(verdict + ", " + std::to_string(bands) + " candidate bands");
}
BENCHMARK(BM_Diagnose10s48k)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
