// Spectral primitives on 10 s of a bearing-like signal at 48 kHz (480,000 samples):
//   SES for one band including the record's forward FFT, the fast kurtogram, and both together
//   (the kurtogram reuses the SES analyser's FFT), as `spall diagnose` runs them.
// Compare with scripts/bench_scipy_ses.py (numpy/scipy SES of the same kind of signal).
// Run: build-<you>/bench/dsp_benchmark --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include "dsp/envelope.h"
#include "dsp/fft.h"
#include "dsp/kurtogram.h"
#include "dsp/prewhiten.h"
#include "dsp/record_check.h"
#include "dsp/spectra.h"
#include "dsp/statistics.h"
#include "tests/dsp/spectral_test_signals.h"

namespace {

using namespace spallkit::dsp;

const std::vector<double>& Signal() {
  static const std::vector<double> x = test_signals::MakeBearingLikeSignal({});
  return x;
}
constexpr double kFs = 48000;
const Band kBand{7000, 11000};  // around the 9 kHz resonance

void BM_ForwardFftOnly(benchmark::State& state) {
  const auto& x = Signal();
  for (auto _ : state) {
    EnvelopeAnalyzer analyzer(x, kFs);
    benchmark::DoNotOptimize(analyzer.spectrum().data());
  }
}
BENCHMARK(BM_ForwardFftOnly)->Unit(benchmark::kMillisecond);

// (a) SES alone, max alpha = the band width (4 kHz), forward FFT included.
void BM_SesOneBand(benchmark::State& state) {
  const auto& x = Signal();
  for (auto _ : state) {
    EnvelopeSpectrum ses = SquaredEnvelopeSpectrum(x, kFs, kBand);
    benchmark::DoNotOptimize(ses.level.data());
  }
}
BENCHMARK(BM_SesOneBand)->Unit(benchmark::kMillisecond);

// SES for a further band on an existing analyser (the forward FFT is not repeated).
void BM_SesExtraBand(benchmark::State& state) {
  EnvelopeAnalyzer analyzer(Signal(), kFs);
  for (auto _ : state) {
    EnvelopeSpectrum ses = analyzer.Compute(kBand, {.max_alpha_hz = 1000});
    benchmark::DoNotOptimize(ses.level.data());
  }
}
BENCHMARK(BM_SesExtraBand)->Unit(benchmark::kMillisecond);

// (b) the kurtogram (its own forward FFT included), automatic depth (L = 9 here: 18 rows).
void BM_Kurtogram(benchmark::State& state) {
  const auto& x = Signal();
  KurtogramOptions options;
  options.max_level = static_cast<int>(state.range(0));
  options.threads = static_cast<int>(state.range(1));
  for (auto _ : state) {
    Kurtogram k = FastKurtogram(x, kFs, options);
    benchmark::DoNotOptimize(k.best.kurtosis);
  }
}
BENCHMARK(BM_Kurtogram)
    ->ArgNames({"max_level", "threads"})
    ->Args({0, 1})
    ->Args({0, 2})
    ->Args({6, 1})
    ->Args({5, 1})
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// (c) kurtogram + SES of its best band, one forward FFT shared, as in `spall diagnose`.
void BM_KurtogramThenSes(benchmark::State& state) {
  const auto& x = Signal();
  KurtogramOptions options;
  options.threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    EnvelopeAnalyzer analyzer(x, kFs);
    Kurtogram k = FastKurtogram(analyzer, options);
    EnvelopeSpectrum ses = analyzer.Compute(k.best.band(), {.max_alpha_hz = 1000});
    benchmark::DoNotOptimize(ses.level.data());
  }
}
BENCHMARK(BM_KurtogramThenSes)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_WelchPsd(benchmark::State& state) {
  const auto& x = Signal();
  for (auto _ : state) {
    Spectrum s = WelchPsd(x, kFs);
    benchmark::DoNotOptimize(s.psd.data());
  }
}
BENCHMARK(BM_WelchPsd)->Unit(benchmark::kMillisecond);

void BM_Stft(benchmark::State& state) {
  const auto& x = Signal();
  for (auto _ : state) {
    Spectrogram s = Stft(x, kFs);
    benchmark::DoNotOptimize(s.power_db.data());
  }
}
BENCHMARK(BM_Stft)->Unit(benchmark::kMillisecond);

void BM_TimeStatistics(benchmark::State& state) {
  const auto& x = Signal();
  for (auto _ : state) benchmark::DoNotOptimize(ComputeTimeStatistics(x).kurtosis);
}
BENCHMARK(BM_TimeStatistics)->Unit(benchmark::kMillisecond);

// The record checks before a diagnosis: finiteness, range, median and MAD of every 4th sample,
// outliers, clipping.
void BM_CheckRecord(benchmark::State& state) {
  const auto& x = Signal();
  for (auto _ : state) benchmark::DoNotOptimize(CheckRecord(x).robust_sigma);
}
BENCHMARK(BM_CheckRecord)->Unit(benchmark::kMillisecond);

// One single-precision transform of a kurtogram size (7,680 x 2^k: the deepest binary row's m at
// 10 s, 48 kHz, L = 6, and its parents' halves) with FFTW_ESTIMATE plans (what the kurtogram uses)
// and FFTW_MEASURE plans (made once, before the timing; making them takes seconds).
void BM_FftFloat(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto rigor = state.range(1) ? PlanRigor::kMeasure : PlanRigor::kEstimate;
  ComplexFftF fft(n, +1, rigor);
  auto in = AllocateComplexF(n), out = AllocateComplexF(n);
  for (int i = 0; i < n; ++i) in[i] = {static_cast<float>(i % 7), static_cast<float>(i % 5)};
  for (auto _ : state) {
    fft.Execute(in.get(), out.get());
    benchmark::DoNotOptimize(out.get());
  }
}
BENCHMARK(BM_FftFloat)
    ->ArgNames({"n", "measure"})
    ->Args({15360, 0})
    ->Args({15360, 1})
    ->Args({61440, 0})
    ->Args({61440, 1})
    ->Unit(benchmark::kMicrosecond);

void BM_CepstrumPrewhiten(benchmark::State& state) {
  const auto& x = Signal();
  for (auto _ : state) {
    std::vector<double> w = CepstrumPrewhiten(x);
    benchmark::DoNotOptimize(w.data());
  }
}
BENCHMARK(BM_CepstrumPrewhiten)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
