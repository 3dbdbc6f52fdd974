// Identification cost per record (docs/IDENTIFY.md, docs/PERFORMANCE.md): diagnosis excluded, one
// thread, 1 s synthetic records of an N205EM at 1200 rpm (10 dB) with one, two (adjacent) and three
// spalled rollers. The budget is 5 s of CPU per 1 s record.
//   build/bench/identify_benchmark --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>

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
  identify::IdentifyOptions o = identify::SignalModelOptions();
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

// A small synthetic check of the whole identification (signal model of
// identify/synthetic_record.h, not a simulator): `records` records with random speed 900-1800
// rpm, load 5-15 kN, 0-3 defective rollers at random slots and spin phases, one width 0.5-2.5
// mm per record, SNR 0-20 dB in the resonance band, 1 s at 20 kHz. Counters: counts stated and
// right / stated and wrong, widths stated, within 15 %, intervals covering the truth.
//   build/bench/identify_benchmark --benchmark_filter=SyntheticCheck
void BM_SyntheticCheck(benchmark::State& state) {
  const int records = static_cast<int>(state.range(0));
  double count_right = 0, count_wrong = 0, count_none = 0, width_stated = 0, width_15 = 0,
         width_covered = 0, spalled = 0;
  for (auto _ : state) {
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int r = 0; r < records; ++r) {
      identify::SyntheticRecordSpec s;
      const double rpm = 900.0 + 900.0 * u(rng);
      s.shaft_hz = rpm / 60.0;
      s.radial_load_n = 5000.0 + 10000.0 * u(rng);
      s.snr_db = 20.0 * u(rng);
      s.seed = 1000 + r;
      const int k = static_cast<int>(4 * u(rng));
      const double width = (0.5 + 2.0 * u(rng)) * 1e-3;
      std::vector<int> slots;
      while (static_cast<int>(slots.size()) < k) {
        const int slot = static_cast<int>(13 * u(rng));
        if (std::find(slots.begin(), slots.end(), slot) == slots.end()) slots.push_back(slot);
      }
      for (int slot : slots) {
        identify::SyntheticRoller roller;
        roller.slot = slot;
        roller.width_m = width;
        roller.spin_phase_rad = 6.283185307179586 * u(rng);
        s.rollers.push_back(roller);
      }
      Record rec = identify::MakeSyntheticRecord(s);
      if (k == 0) {  // no roller, no signal to set a noise level against: unit white noise
        std::mt19937_64 noise_rng(s.seed);  // its own stream: the other records stay the same
        std::normal_distribution<double> noise(0.0, 1.0);
        for (double& x : rec.samples) x = noise(noise_rng);
      }
      const BearingGeometry g = CatalogBearing("N205EM");
      const dsp::Diagnosis d = dsp::Diagnose(rec, g, s.shaft_hz);
      identify::IdentifyOptions o = identify::SignalModelOptions();
      o.radial_load_n = s.radial_load_n;
      const identify::Identification id = identify::Identify(rec, g, s.shaft_hz, d, o);
      if (!id.count_identifiable) {
        ++count_none;
        if (k == 0) ++count_right;  // nothing stated for a healthy record is right
      } else if (id.count == k) {
        ++count_right;
      } else {
        ++count_wrong;
      }
      if (k > 0) ++spalled;
      if (k > 0 && id.width_identifiable) {
        ++width_stated;
        if (std::abs(id.width_m - width) <= 0.15 * width) ++width_15;
        if (id.width_low_m <= width && width <= id.width_high_m) ++width_covered;
      }
    }
  }
  state.counters["records"] = records;
  state.counters["count_right"] = count_right;
  state.counters["count_wrong"] = count_wrong;
  state.counters["count_not_stated"] = count_none;
  state.counters["spalled"] = spalled;
  state.counters["width_stated"] = width_stated;
  state.counters["width_within_15pct"] = width_15;
  state.counters["width_covered"] = width_covered;
}
BENCHMARK(BM_SyntheticCheck)->Arg(40)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
