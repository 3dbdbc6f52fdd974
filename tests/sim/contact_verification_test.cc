// The contact verification cases (sim/verify/contact_cases.cc) as tests: each compares a computed
// quantity with its analytic reference within the case's tolerance.
#include <gtest/gtest.h>

#include "sim/verify/verification.h"

namespace spallkit::sim::verify {
namespace {

void ExpectAllPass(const std::string& filter, size_t expected) {
  std::vector<CaseResult> results;
  AppendContactCases(&results, filter);
  ASSERT_EQ(results.size(), expected) << filter;
  for (const CaseResult& r : results) {
    EXPECT_TRUE(r.pass) << r.name << ": " << r.quantity << " reference " << r.reference
                        << " computed " << r.computed << " error " << r.error << " > "
                        << r.tolerance << " (" << r.note << ")";
    std::printf("%-26s %-48s ref %-12.5g got %-12.5g err %.4f tol %.3f  %s\n",
                r.name.c_str(),
                r.quantity.c_str(),
                r.reference,
                r.computed,
                r.error,
                r.tolerance,
                r.note.c_str());
  }
}

TEST(ContactVerification, HertzDiscBetweenRigidFlats) {
  ExpectAllPass("hertz: disc between flats", 3);
}
TEST(ContactVerification, HertzDiscInBore) { ExpectAllPass("hertz: disc in bore", 1); }
TEST(ContactVerification, FrictionBlockSticksThenSlides) { ExpectAllPass("friction:", 3); }
TEST(ContactVerification, DiscImpactConservesEnergy) { ExpectAllPass("impact: two discs", 1); }
TEST(ContactVerification, BlockImpactKeepsHourglassEnergySmall) {
  ExpectAllPass("impact: two blocks", 1);
}

}  // namespace
}  // namespace spallkit::sim::verify
