// DiagnoseOptions::threads: the band search and the kurtogram run on several threads, and the
// Diagnosis must be bit-identical to the single-thread one (same bands compared in the same order).
#include <gtest/gtest.h>

#include <string>

#include "core/bearing.h"
#include "dsp/diagnose.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace spallkit::dsp {
namespace {

using spallkit::testing::FaultSignalSpec;
using spallkit::testing::MakeFaultSignal;

FaultSignalSpec Spec(double shaft_hz, double rate_hz) {
  FaultSignalSpec s;
  s.fs_hz = 24000.0;
  s.duration_s = 2.0;
  s.shaft_hz = shaft_hz;
  s.shaft_amplitude = 0.5;
  s.mains_amplitude = 0.2;
  s.noise_rms = 0.4;
  s.amplitude = 3.0;
  s.rate_hz = rate_hz;
  s.resonance_hz = 6500.0;
  s.seed = 11;
  return s;
}

// Full JSON (every score, p-value, line, band and the searched count) for 1, 2 and 3 threads,
// for a faulty record (staged search stops after stage 1) and a healthy one (all bands).
TEST(DiagnoseThreads, IdenticalForEveryThreadCount) {
  const auto g = CatalogBearing("6205");
  const double shaft_hz = 1797.0 / 60.0;
  const BearingFrequencies f = ComputeFrequencies(g, shaft_hz);
  for (const double rate : {0.99 * f.bpfo_hz, 0.0}) {
    const Record record = spallkit::testing::MakeFaultRecord(Spec(shaft_hz, rate));
    DiagnoseOptions o;
    o.threads = 1;
    const Diagnosis one = Diagnose(record, g, shaft_hz, o);
    EXPECT_EQ(one.verdict, rate > 0 ? Verdict::kOuterRace : Verdict::kHealthy);
    if (rate == 0.0) {
      EXPECT_EQ(one.searched_bands, one.candidate_bands);
    }
    const std::string reference = one.ToJson(0);
    for (const int threads : {2, 3}) {
      o.threads = threads;
      const Diagnosis many = Diagnose(record, g, shaft_hz, o);
      EXPECT_EQ(many.ToJson(0), reference) << threads << " threads, rate " << rate;
    }
  }
}

TEST(DiagnoseThreads, NegativeCountRejected) {
  DiagnoseOptions o;
  o.threads = -1;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("threads"), std::string::npos);
}

}  // namespace
}  // namespace spallkit::dsp
