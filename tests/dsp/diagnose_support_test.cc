// A family is claimed only when the record holds DiagnoseOptions::min_periods periods of its
// fundamental: a cage-rate impulse train on a 1 s record (12 cage turns) is reported with its
// evidence but not claimed, and still explains its own lines, so that they are not taken for
// another family's (BPFO = Z f_c, f_b near a cage harmonic): the record is healthy. The same
// signal over 5 s (60 turns) is claimed.
#include <gtest/gtest.h>

#include "core/bearing.h"
#include "dsp/diagnose.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace spallkit::dsp {
namespace {

Record CageRecord(double seconds) {
  const auto kin = ComputeFrequencies(CatalogBearing("6205"), 1797 / 60.0);
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = 12000;
  s.duration_s = seconds;
  s.rate_hz = kin.cage_hz;
  s.amplitude = 3.0;
  s.noise_rms = 0.3;
  return spallkit::testing::MakeFaultRecord(s);
}

const FamilyDetection& Cage(const Diagnosis& d) {
  for (const auto& f : d.faults)
    if (f.component == FaultComponent::kCage) return f;
  throw std::logic_error("no cage family");
}

TEST(DiagnoseSupport, CageCombOnAShortRecordIsNotClaimed) {
  DiagnoseOptions o;
  o.min_periods = 0.0;
  const Diagnosis unrestricted = Diagnose(CageRecord(1.0), CatalogBearing("6205"), 1797 / 60.0, o);
  ASSERT_TRUE(Cage(unrestricted).detected) << Cage(unrestricted).reason;
  const Diagnosis d = Diagnose(CageRecord(1.0), CatalogBearing("6205"), 1797 / 60.0);
  EXPECT_FALSE(Cage(d).detected);
  EXPECT_NE(d.verdict, Verdict::kCage);
  EXPECT_EQ(d.verdict, Verdict::kHealthy) << d.BriefReport();
  EXPECT_NE(Cage(d).reason.find("not claimed"), std::string::npos) << Cage(d).reason;
  const Diagnosis longer = Diagnose(CageRecord(5.0), CatalogBearing("6205"), 1797 / 60.0);
  EXPECT_EQ(longer.verdict, Verdict::kCage) << Cage(longer).reason;
}

}  // namespace
}  // namespace spallkit::dsp
