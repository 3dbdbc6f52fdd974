// Varying compliance is not an outer-race fault: the rollers passing the load zone make every
// healthy bearing's response periodic at Z f_c = BPFO. That response is deterministic (discrete
// raw lines at n BPFO), and its squared envelope carries a strong BPFO comb; a spall's impacts
// jitter with the rollers' slip. DiagnoseOptions::confirm_outer_race asks the comb to survive
// cepstrum pre-whitening, which flattens discrete lines.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/bearing.h"
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

TEST(DiagnoseCompliance, DeterministicBpfoResponseIsNotAnOuterRaceFault) {
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const Record r = PeriodicAtBpfo(seed);
    DiagnoseOptions o;
    o.threads = 1;
    o.confirm_outer_race = false;
    const Diagnosis raw = Diagnose(r, CatalogBearing("N205EM"), kShaftHz, o);
    ASSERT_EQ(raw.verdict, Verdict::kOuterRace) << "the test signal must feed the BPFO comb";
    o.confirm_outer_race = true;
    const Diagnosis d = Diagnose(r, CatalogBearing("N205EM"), kShaftHz, o);
    EXPECT_EQ(d.verdict, Verdict::kHealthy) << d.BriefReport();
    bool said = false;
    for (const auto& f : d.faults)
      said |= f.component == FaultComponent::kOuterRace &&
              f.reason.find("pre-whitening") != std::string::npos;
    EXPECT_TRUE(said) << d.BriefReport();
  }
}

TEST(DiagnoseCompliance, JitteredImpactsAtBpfoStayAnOuterRaceFault) {
  const auto kin = ComputeFrequencies(CatalogBearing("N205EM"), kShaftHz);
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = kFs;
  s.duration_s = kSeconds;
  s.rate_hz = kin.bpfo_hz;
  s.amplitude = 2.0;
  s.resonance_hz = 2500.0;
  s.jitter = 0.005;
  s.noise_rms = 0.4;
  Record r;
  r.sample_rate_hz = kFs;
  r.samples = spallkit::testing::MakeFaultSignal(s);
  DiagnoseOptions o;
  o.threads = 1;
  const Diagnosis d = Diagnose(r, CatalogBearing("N205EM"), kShaftHz, o);
  EXPECT_EQ(d.verdict, Verdict::kOuterRace) << d.BriefReport();
}

}  // namespace
}  // namespace spallkit::dsp
