// The element/solver verification cases must pass (each compares with an analytic reference).
#include <gtest/gtest.h>

#include "sim/verify/verification.h"

namespace spallkit::sim::verify {
namespace {

void ExpectCasesPass(const std::string& filter, size_t expected_count) {
  std::vector<CaseResult> results;
  AppendFeCases(&results, filter);
  ASSERT_EQ(results.size(), expected_count) << filter;
  for (const auto& r : results) {
    EXPECT_TRUE(r.pass) << r.name << ": reference " << r.reference << ", computed " << r.computed
                        << ", error " << r.error << " > tolerance " << r.tolerance << " (" << r.note
                        << ")";
    EXPECT_LE(r.error, r.tolerance) << r.name;
  }
}

TEST(VerifyFe, PatchTest) { ExpectCasesPass("patch", 1); }
TEST(VerifyFe, PrescribedRigidRotationKeepsStressAtRoundOff) {
  ExpectCasesPass("prescribed rigid rotation", 1);
}
TEST(VerifyFe, FreeSpinningRingHoopStressAndSpin) { ExpectCasesPass("rotation: ", 3); }
TEST(VerifyFe, WaveSpeeds) { ExpectCasesPass("wave", 2); }
TEST(VerifyFe, CantileverFrequencyHourglassAndEnergy) { ExpectCasesPass("cantilever", 3); }

TEST(VerifyFe, FilterSelectsNothingForUnknownName) {
  std::vector<CaseResult> results;
  AppendFeCases(&results, "no such case");
  EXPECT_TRUE(results.empty());
}

}  // namespace
}  // namespace spallkit::sim::verify
