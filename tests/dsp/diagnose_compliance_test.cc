// Varying compliance is not an outer-race fault: the rollers passing the load zone make every
// healthy bearing's response periodic at Z f_c = BPFO. That response is deterministic (discrete
// raw lines at n BPFO), and its squared envelope carries a strong BPFO comb; a spall's impacts
// jitter with the rollers' slip. DiagnoseOptions::confirm_outer_race asks the comb to survive
// cepstrum pre-whitening, which flattens discrete lines, in a band above the low orders of BPFO
// where that response has its lines (DiagnoseOptions::outer_race_min_band_orders).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/bearing.h"
#include "core/error.h"
#include "dsp/diagnose.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace spallkit::dsp {
namespace {

constexpr double kFs = 20000.0, kShaftHz = 20.0, kSeconds = 2.0;

// A periodic response at BPFO: its harmonics between 1.5 and 3.5 kHz with random fixed phases
// and a resonance-shaped amplitude, in white noise. Each harmonic sits on an FFT bin of the
// record (within 1/(2T) of k BPFO), as a stationary line of a long record does.
Record PeriodicAtBpfo(unsigned seed) {
  const auto kin = ComputeFrequencies(CatalogBearing("N205EM"), kShaftHz);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 2.0 * std::numbers::pi);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const int n = static_cast<int>(kFs * kSeconds);
  Record r;
  r.sample_rate_hz = kFs;
  r.samples.assign(n, 0.0);
  for (int k = static_cast<int>(1500 / kin.bpfo_hz); k * kin.bpfo_hz < 3500; ++k) {
    const double f = std::round(k * kin.bpfo_hz * kSeconds) / kSeconds, phase = u(rng);
    const double a = 1.0 / (1.0 + std::pow((f - 2500.0) / 600.0, 2));
    for (int i = 0; i < n; ++i)
      r.samples[i] += a * std::cos(2.0 * std::numbers::pi * f * i / kFs + phase);
  }
  for (double& v : r.samples) v += 0.3 * gauss(rng);
  return r;
}

// Impacts at BPFO ringing one resonance, jittered by the rollers' slip: an outer-race spall.
Record JitteredImpactsAtBpfo(double fs_hz, double resonance_hz) {
  const auto kin = ComputeFrequencies(CatalogBearing("N205EM"), kShaftHz);
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = fs_hz;
  s.duration_s = kSeconds;
  s.rate_hz = kin.bpfo_hz;
  s.amplitude = 2.0;
  s.resonance_hz = resonance_hz;
  s.jitter = 0.005;
  s.noise_rms = 0.4;
  Record r;
  r.sample_rate_hz = fs_hz;
  r.samples = spallkit::testing::MakeFaultSignal(s);
  return r;
}

Diagnosis DiagnoseOneThread(const Record& r, DiagnoseOptions o = {}) {
  o.threads = 1;
  return Diagnose(r, CatalogBearing("N205EM"), kShaftHz, o);
}

TEST(DiagnoseCompliance, DeterministicBpfoResponseIsNotAnOuterRaceFault) {
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const Record r = PeriodicAtBpfo(seed);
    DiagnoseOptions o;
    o.confirm_outer_race = false;
    const Diagnosis raw = DiagnoseOneThread(r, o);
    ASSERT_EQ(raw.verdict, Verdict::kOuterRace) << "the test signal must feed the BPFO comb";
    o.confirm_outer_race = true;
    o.outer_race_min_band_orders = 0.0;  // the pre-whitening alone flattens these lines
    const Diagnosis d = DiagnoseOneThread(r, o);
    EXPECT_EQ(d.verdict, Verdict::kHealthy) << d.BriefReport();
    bool said = false;
    for (const auto& f : d.faults)
      said |= f.component == FaultComponent::kOuterRace &&
              f.reason.find("pre-whitening") != std::string::npos;
    EXPECT_TRUE(said) << d.BriefReport();
  }
}

TEST(DiagnoseCompliance, JitteredImpactsAtBpfoStayAnOuterRaceFault) {
  const Diagnosis d = DiagnoseOneThread(JitteredImpactsAtBpfo(kFs, 2500.0));
  EXPECT_EQ(d.verdict, Verdict::kOuterRace) << d.BriefReport();
}

// The varying compliance as the simulated healthy N205EM shows it: a smooth load change per roller
// passage (lines at orders 1..13 of BPFO, falling off with the order) and the ring's low
// resonance, whose broadband response the passing rollers modulate smoothly at BPFO. The lines
// fall between FFT bins (1.1 s record), and the modulated part survives pre-whitening, in a low
// band only: above it the record is white noise.
Record SmoothPassagesThroughALowResonance() {
  const auto kin = ComputeFrequencies(CatalogBearing("N205EM"), kShaftHz);
  constexpr double kDuration = 1.1, kResonanceHz = 900.0, kZeta = 0.1;
  const int n = static_cast<int>(kFs * kDuration);
  const double two_pi = 2.0 * std::numbers::pi;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Record r;
  r.sample_rate_hz = kFs;
  r.samples.assign(n, 0.0);
  for (int k = 1; k <= 13; ++k) {
    const double f = k * kin.bpfo_hz, q = f / kResonanceHz;
    const double gain = std::exp(-0.3 * k) / std::hypot(1.0 - q * q, 2.0 * kZeta * q);
    for (int i = 0; i < n; ++i) r.samples[i] += gain * std::cos(two_pi * f * i / kFs);
  }
  // White noise through the resonance (a two-pole resonator), modulated by the passages.
  const double w = two_pi * kResonanceHz / kFs, radius = std::exp(-kZeta * w);
  const double a1 = 2.0 * radius * std::cos(w), a2 = -radius * radius;
  double y1 = 0.0, y2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double y = gauss(rng) + a1 * y1 + a2 * y2;
    y2 = y1;
    y1 = y;
    double passage = 1.0;
    for (int k = 1; k <= 3; ++k)
      passage += std::pow(0.5, k) * std::cos(two_pi * k * kin.bpfo_hz * i / kFs);
    r.samples[i] += 0.05 * passage * y + 0.01 * gauss(rng);
  }
  return r;
}

TEST(DiagnoseCompliance, LowOrderBpfoLinesAreNotAnOuterRaceFaultEvenWhenTheySurviveWhitening) {
  const Record r = SmoothPassagesThroughALowResonance();
  DiagnoseOptions o;
  o.outer_race_min_band_orders = 0.0;  // pre-whitening alone
  const Diagnosis any_band = DiagnoseOneThread(r, o);
  ASSERT_EQ(any_band.verdict, Verdict::kOuterRace)
      << "the test signal must fool the pre-whitening alone\n"
      << any_band.BriefReport();
  const Diagnosis d = DiagnoseOneThread(r);
  EXPECT_EQ(d.verdict, Verdict::kHealthy) << d.BriefReport();
  bool said = false;
  for (const auto& f : d.faults)
    said |=
        f.component == FaultComponent::kOuterRace && f.reason.find("x BPFO") != std::string::npos;
  EXPECT_TRUE(said) << d.BriefReport();
}

TEST(DiagnoseCompliance,
     ImpactsRingingOnlyALowResonanceAreConfirmedWhereTheRecordAllowsNoHigherBand) {
  // fs 4 kHz: no candidate band starts at 20 x BPFO (2.16 kHz) below fs/2, so any band confirms
  // the impacts and the Diagnosis says the record cannot tell them from varying compliance.
  const Diagnosis d = DiagnoseOneThread(JitteredImpactsAtBpfo(4000.0, 1500.0));
  EXPECT_EQ(d.verdict, Verdict::kOuterRace) << d.BriefReport();
  bool warned = false;
  for (const auto& w : d.warnings) warned |= w.find("cannot tell") != std::string::npos;
  EXPECT_TRUE(warned) << d.BriefReport();
}

TEST(DiagnoseCompliance, CandidateBandsStartAtTheRequestedFrequency) {
  const Record r = JitteredImpactsAtBpfo(kFs, 2500.0);
  DiagnoseOptions o;
  o.min_band_low_hz = 4000.0;
  const Diagnosis d = DiagnoseOneThread(r, o);
  EXPECT_GE(d.band.low_hz, 4000.0) << d.BriefReport();
  o.min_band_low_hz = 0.49 * kFs;  // no band of the needed width fits above
  EXPECT_THROW(DiagnoseOneThread(r, o), InputError);
  std::string error;
  o.min_band_low_hz = -1.0;
  EXPECT_FALSE(o.IsValid(&error));
  o.min_band_low_hz = 0.0;
  o.outer_race_min_band_orders = -1.0;
  EXPECT_FALSE(o.IsValid(&error));
}

}  // namespace
}  // namespace spallkit::dsp
