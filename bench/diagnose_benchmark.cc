// The whole `spall diagnose` analysis (kurtogram + candidate-band SES + fault-band detection; no
// I/O, no plots) on 10 s at 48 kHz of a synthetic outer-race record (6205 at 1797 rpm), and its
// per-band stages (one candidate band's SES, robust floor, and the four family combs) so that a
// change can be attributed.
// Run: build-<you>/bench/diagnose_benchmark --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include "core/bearing.h"
#include "dsp/diagnose.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace {

using namespace spallkit::dsp;
using spallkit::Record;

Record MakeRecord(bool faulty) {
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = 48000;
  s.duration_s = 10.0;
  s.rate_hz = faulty ? 107.36 * 0.99 : 0.0;
  s.resonance_hz = 12000;
  s.amplitude = 3.0;
  s.noise_rms = 0.4;
  s.shaft_hz = 29.95;
  s.shaft_amplitude = 0.5;
  s.mains_amplitude = 0.2;
  if (!faulty) {  // a healthy bearing's weak BPFO-order line
    s.extra_line_hz = 107.36;
    s.extra_line_amplitude = 0.3;
  }
  Record rec;
  rec.samples = spallkit::testing::MakeFaultSignal(s);
  rec.sample_rate_hz = s.fs_hz;
  return rec;
}

const Record& TheRecord() {
  static const Record r = MakeRecord(true);
  return r;
}

constexpr double kShaftHz = 1797 / 60.0;

// Args: first_bands (16, the default staged search; 0, every candidate band in one go), threads
// (DiagnoseOptions::threads: 1, single thread; 2, the band search and the kurtogram's chains on
// two threads; the results are identical).
void RunDiagnose(benchmark::State& state, const Record& record) {
  const auto bearing = spallkit::CatalogBearing("6205");
  DiagnoseOptions options;
  options.first_bands = static_cast<int>(state.range(0));
  options.threads = static_cast<int>(state.range(1));
  std::string verdict;
  int bands = 0, searched = 0;
  for (auto _ : state) {
    const auto d = Diagnose(record, bearing, kShaftHz, options);
    verdict = VerdictName(d.verdict);
    bands = d.candidate_bands;
    searched = d.searched_bands;
    benchmark::DoNotOptimize(d.faults.data());
  }
  state.SetLabel(verdict + ", " + std::to_string(searched) + " of " + std::to_string(bands) +
                 " candidate bands searched");
}

// Outer-race fault record (the fault record of docs/PERFORMANCE.md, "Diagnosis").
void BM_Diagnose10s48k(benchmark::State& state) { RunDiagnose(state, TheRecord()); }
BENCHMARK(BM_Diagnose10s48k)
    ->ArgNames({"first_bands", "threads"})
    ->Args({16, 1})
    ->Args({0, 1})
    ->Args({16, 2})
    ->Args({0, 2})
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);

// Healthy record (noise, shaft, mains and a weak BPFO-order line): nothing stops the search, so
// this is the cost of searching every candidate band.
void BM_DiagnoseHealthy10s48k(benchmark::State& state) {
  static const Record healthy = MakeRecord(false);
  RunDiagnose(state, healthy);
}
BENCHMARK(BM_DiagnoseHealthy10s48k)
    ->ArgNames({"first_bands", "threads"})
    ->Args({16, 1})
    ->Args({16, 2})
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);

// One candidate band as Diagnose sees it: 9-12 kHz (3 kHz wide), SES up to the highest fault line
// plus half a floor window (~920 Hz, ~9,200 bins).
struct BandFixture {
  EnvelopeAnalyzer analyzer{TheRecord().samples, TheRecord().sample_rate_hz};
  Band band{9000, 12000};
  double max_alpha_hz = 920.0;
  std::vector<FaultFamily> families =
      MakeFaultFamilies(ComputeFrequencies(spallkit::CatalogBearing("6205"), kShaftHz));
};

void BM_BandSes(benchmark::State& state) {
  BandFixture f;
  for (auto _ : state) {
    const EnvelopeSpectrum ses = f.analyzer.Compute(f.band, {.max_alpha_hz = f.max_alpha_hz});
    benchmark::DoNotOptimize(ses.level.data());
  }
}
BENCHMARK(BM_BandSes)->Unit(benchmark::kMicrosecond);

// The same band's SES power as Diagnose forms it (single-precision transforms).
void BM_BandSesPowerFast(benchmark::State& state) {
  BandFixture f;
  for (auto _ : state) {
    const std::vector<double> p = f.analyzer.SesPowerFast(f.band, f.max_alpha_hz, nullptr);
    benchmark::DoNotOptimize(p.data());
  }
}
BENCHMARK(BM_BandSesPowerFast)->Unit(benchmark::kMicrosecond);

void BM_BandFloor(benchmark::State& state) {
  BandFixture f;
  const EnvelopeSpectrum ses = f.analyzer.Compute(f.band, {.max_alpha_hz = f.max_alpha_hz});
  std::vector<double> power(ses.level.size());
  for (size_t i = 0; i < power.size(); ++i) power[i] = ses.level[i] * ses.level[i];
  for (auto _ : state) {
    const NormalizedSpectrum n = NormalizeSpectrum(power, ses.resolution_hz);
    benchmark::DoNotOptimize(n.z.data());
  }
  state.SetLabel(std::to_string(power.size()) + " bins");
}
BENCHMARK(BM_BandFloor)->Unit(benchmark::kMicrosecond);

void BM_BandFourCombs(benchmark::State& state) {
  BandFixture f;
  const EnvelopeSpectrum ses = f.analyzer.Compute(f.band, {.max_alpha_hz = f.max_alpha_hz});
  std::vector<double> power(ses.level.size());
  for (size_t i = 0; i < power.size(); ++i) power[i] = ses.level[i] * ses.level[i];
  const NormalizedSpectrum n = NormalizeSpectrum(power, ses.resolution_hz);
  DetectionContext ctx;
  ctx.shaft_hz = kShaftHz;
  ctx.multiplicity = 256;
  // As Diagnose runs it: the comb plans are made once per spectrum size, each band pays one
  // pair-score pass and the four plan evaluations.
  std::vector<CombSearch> plans;
  for (const auto& fam : f.families)
    plans.emplace_back(fam, ctx, DetectionOptions{}, n.resolution_hz, static_cast<int>(n.z.size()));
  for (auto _ : state) {
    const std::vector<double> scores = PairScores(n);
    for (const auto& plan : plans) {
      const FamilyDetection d = plan.Detect(n, scores);
      benchmark::DoNotOptimize(d.p_value);
    }
  }
}
BENCHMARK(BM_BandFourCombs)->Unit(benchmark::kMicrosecond);

// The same four combs as one-off DetectFamily calls (plan and pair scores made per call), as the
// joint explanation's re-tests on the chosen band run them.
void BM_BandFourCombsOneOff(benchmark::State& state) {
  BandFixture f;
  const EnvelopeSpectrum ses = f.analyzer.Compute(f.band, {.max_alpha_hz = f.max_alpha_hz});
  std::vector<double> power(ses.level.size());
  for (size_t i = 0; i < power.size(); ++i) power[i] = ses.level[i] * ses.level[i];
  const NormalizedSpectrum n = NormalizeSpectrum(power, ses.resolution_hz);
  DetectionContext ctx;
  ctx.shaft_hz = kShaftHz;
  ctx.multiplicity = 256;
  for (auto _ : state) {
    for (const auto& fam : f.families) {
      const FamilyDetection d = DetectFamily(n, fam, ctx);
      benchmark::DoNotOptimize(d.p_value);
    }
  }
}
BENCHMARK(BM_BandFourCombsOneOff)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
