// PalmgrenPowerNear (sim/bearing/palmgren_power.h) against std::pow on penetration histories like
// a contact's: slow drifts, which the expansion serves, and jumps and rattles, which refresh it.
#include "sim/bearing/palmgren_power.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace spallkit::sim {
namespace {

TEST(PalmgrenPowerTest, MatchesStdPowToRoundingAlongAContactsHistory) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> step(0.0, 1.0);
  double d0 = 0.0, p0 = 0.0, d = 1e-5;
  double worst = 0.0;
  int refreshed = 0;
  const int kCalls = 200000;
  for (int i = 0; i < kCalls; ++i) {
    // Relative moves of 1e-4 (a loaded roller), now and then 3e-2 (a rattling one), and a jump
    // by a decade every 10,000 calls (a spall edge).
    const double size = i % 10000 == 0 ? 1.0 : (i % 50 == 0 ? 3e-2 : 1e-4);
    d = std::clamp(d * std::exp(size * step(rng)), 1e-9, 1e-4);
    const double before = d0;
    const double got = PalmgrenPowerNear(d, &d0, &p0);
    refreshed += d0 != before;
    const double exact = std::pow(d, 10.0 / 9.0);
    worst = std::max(worst, std::abs(got / exact - 1.0));
  }
  EXPECT_LT(worst, 1e-12);
  // The expansion does the work: std::pow on a few calls in a hundred.
  EXPECT_LT(refreshed, kCalls / 20);
  EXPECT_GT(refreshed, 0);
}

TEST(PalmgrenPowerTest, FirstCallAndOutOfReachCallsAreExact) {
  double d0 = 0.0, p0 = 0.0;
  EXPECT_EQ(PalmgrenPowerNear(2e-6, &d0, &p0), std::pow(2e-6, 10.0 / 9.0));
  EXPECT_EQ(d0, 2e-6);
  EXPECT_EQ(PalmgrenPowerNear(3e-6, &d0, &p0), std::pow(3e-6, 10.0 / 9.0));  // 50 % away
  EXPECT_EQ(d0, 3e-6);
  PalmgrenPowerNear(3.0001e-6, &d0, &p0);  // within reach: the point stays
  EXPECT_EQ(d0, 3e-6);
}

}  // namespace
}  // namespace spallkit::sim
