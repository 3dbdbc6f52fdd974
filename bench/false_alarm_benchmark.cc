// Empirical false-alarm rate of the diagnosis (design: DiagnoseOptions::false_alarm_probability
// per record, 1e-3) on healthy-like records, counted over many records; the wall time per record
// comes with it. Each benchmark runs once (Iterations(1)) and reports the counters
//   records, false_alarms, rate (false_alarms / records), design (the per-record budget).
// A false alarm = any fault verdict; each one is printed on stderr with what reproduces it.
//
// Sets:
//   synthetic: coloured noise (a random structural resonance excited by Gaussian noise, plus
//     white noise), shaft harmonics, 60 Hz mains harmonics, and a weak amplitude modulation at
//     the rollers' passing rate Z f_c (varying compliance, present in every healthy rolling
//     bearing), for four bearings (6205, 6203, N205EM, the MFPT bearing) at their test speeds,
//     1, 2 and 5 s long, at 12, 20 and 48.8 kHz.
//   cwru_pieces: the healthy CWRU record 97 (3 s, 48 kHz) cut into 0.5 s and 1 s pieces, each
//     diagnosed with each of the four bearings' kinematics at the record's speed (a healthy record
//     has no fault comb at any bearing's frequencies). Needs the measured records
//     ($SPALLKIT_MEASURED_DIR or ../shared/data/measured); skipped when absent.
// Run: build/bench/false_alarm_benchmark [--benchmark_filter=Synthetic] (Arg: design rate x 1e4,
// so 10 = 1e-3; 500 = 5e-2 checks that the test is calibrated, not only conservative).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/bearing.h"
#include "core/record_io.h"
#include "dsp/diagnose.h"

namespace {

using spallkit::Record;
using namespace spallkit::dsp;

struct Machine {
  const char* name;
  spallkit::BearingGeometry bearing;
  double rpm;
};

std::vector<Machine> Machines() {
  return {{"6205", spallkit::CatalogBearing("6205"), 1797.0},
          {"6203", spallkit::CatalogBearing("6203"), 1750.0},
          {"N205EM", spallkit::CatalogBearing("N205EM"), 1200.0},
          {"MFPT", spallkit::CustomBearing(8, 5.969, 31.623, 0.0), 1500.0}};
}

// Healthy-like record: see the file comment.
Record ColouredNoise(unsigned seed, double seconds, double fs, const Machine& m) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = static_cast<int>(std::lround(seconds * fs));
  const double two_pi = 2.0 * std::numbers::pi;
  const double f_res = (0.05 + 0.35 * u(rng)) * fs;  // resonance between 0.05 and 0.4 fs
  const double zeta = 0.01 + 0.09 * u(rng);
  const double r = std::exp(-zeta * two_pi * f_res / fs);
  const double a1 = 2.0 * r * std::cos(two_pi * f_res / fs), a2 = -r * r;
  const double white = 0.2 + 0.8 * u(rng);  // white-noise share against the resonance
  const double shaft_hz = m.rpm / 60.0;
  const auto kin = spallkit::ComputeFrequencies(m.bearing, shaft_hz);
  const double shaft_amp = 2.0 * u(rng), mains_amp = 1.0 * u(rng);
  const double passing_depth = 0.05 * u(rng);  // Z f_c modulation depth, <= 5 %
  const double phase = two_pi * u(rng);
  std::vector<double> y(n);
  double y1 = 0.0, y2 = 0.0, gain = std::sqrt(1.0 - r * r) * (1.0 - r);  // ~unit variance scale
  for (int i = 0; i < n; ++i) {
    const double t = i / fs;
    const double res = a1 * y1 + a2 * y2 + gauss(rng);
    y2 = y1;
    y1 = res;
    double v = (gain * res + white * gauss(rng)) *
               (1.0 + passing_depth * std::cos(two_pi * kin.bpfo_hz * t + phase));
    for (int k = 1; k <= 3; ++k) v += shaft_amp / k * std::sin(two_pi * k * shaft_hz * t + k);
    for (int k = 1; k <= 3; ++k) v += mains_amp / k * std::sin(two_pi * 60.0 * k * t + 0.7 * k);
    y[i] = v;
  }
  Record rec;
  rec.samples = std::move(y);
  rec.sample_rate_hz = fs;
  rec.source = "synthetic seed " + std::to_string(seed);
  return rec;
}

struct Tally {
  int records = 0, false_alarms = 0, refused = 0;
  double seconds = 0.0;
};

void Count(Tally* t,
           const Record& r,
           const Machine& m,
           const DiagnoseOptions& o,
           const std::string& what) {
  try {
    const auto t0 = std::chrono::steady_clock::now();
    const Diagnosis d = Diagnose(r, m.bearing, m.rpm / 60.0, o);
    t->seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++t->records;
    if (d.verdict != Verdict::kHealthy) {
      ++t->false_alarms;
      std::fprintf(stderr,
                   "false alarm: %s, %s at %.0f rpm: %s (p %.2g, band %.0f-%.0f Hz)\n",
                   what.c_str(),
                   m.name,
                   m.rpm,
                   VerdictName(d.verdict),
                   d.Best()->p_value,
                   d.band.low_hz,
                   d.band.high_hz);
    }
  } catch (const std::exception& e) {
    ++t->refused;
  }
}

void Report(benchmark::State& state, const Tally& t, double design) {
  state.counters["records"] = t.records;
  state.counters["false_alarms"] = t.false_alarms;
  state.counters["refused"] = t.refused;
  state.counters["rate"] = t.records > 0 ? double(t.false_alarms) / t.records : 0.0;
  state.counters["design"] = design;
  state.counters["ms_per_record"] = t.records > 0 ? 1e3 * t.seconds / t.records : 0.0;
}

// 1,008 synthetic records: 4 machines x 3 lengths x 3 rates x 28 seeds.
void BM_FalseAlarmSynthetic(benchmark::State& state) {
  DiagnoseOptions o;
  o.false_alarm_probability = state.range(0) * 1e-4;
  o.threads = 1;
  Tally t;
  for (auto _ : state) {
    unsigned seed = 1;
    for (const Machine& m : Machines())
      for (const double seconds : {1.0, 2.0, 5.0})
        for (const double fs : {12000.0, 20000.0, 48828.0})
          for (int k = 0; k < 28; ++k, ++seed) {
            const double len = fs > 40000 && seconds > 2 ? 2.0 : seconds;  // bound the run time
            Count(&t,
                  ColouredNoise(seed, len, fs, m),
                  m,
                  o,
                  "synthetic seed " + std::to_string(seed) + ", " + std::to_string(len) + " s at " +
                      std::to_string(static_cast<int>(fs)) + " Hz");
          }
  }
  Report(state, t, o.false_alarm_probability);
}
BENCHMARK(BM_FalseAlarmSynthetic)->Arg(10)->Arg(500)->Iterations(1)->Unit(benchmark::kSecond);

std::string MeasuredDir() {
  if (const char* env = std::getenv("SPALLKIT_MEASURED_DIR")) return env;
  return std::string(SPALLKIT_SOURCE_DIR) + "/../shared/data/measured";
}

// Record 97 in pieces (0.5 s: 6, 1 s: 3, disjoint), each with the four bearings' kinematics.
void BM_FalseAlarmCwruPieces(benchmark::State& state) {
  const std::string path = MeasuredDir() + "/cwru_normal_0hp_rec097_DE_48k.csv";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("measured record 97 not found (set SPALLKIT_MEASURED_DIR)");
    return;
  }
  const Record full = spallkit::ReadRecord(path);
  DiagnoseOptions o;
  o.false_alarm_probability = state.range(0) * 1e-4;
  o.threads = 1;
  Tally t;
  for (auto _ : state) {
    for (const double piece_s : {0.5, 1.0}) {
      const size_t len = static_cast<size_t>(piece_s * full.sample_rate_hz);
      for (size_t start = 0; start + len <= full.samples.size(); start += len) {
        Record r = full;
        r.samples.assign(full.samples.begin() + start, full.samples.begin() + start + len);
        for (Machine m : Machines()) {
          m.rpm = 1796.0;  // the record's speed
          Count(&t,
                r,
                m,
                o,
                "record 97 from " + std::to_string(start) + ", " + std::to_string(piece_s) + " s");
        }
      }
    }
  }
  Report(state, t, o.false_alarm_probability);
}
BENCHMARK(BM_FalseAlarmCwruPieces)->Arg(10)->Arg(500)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
