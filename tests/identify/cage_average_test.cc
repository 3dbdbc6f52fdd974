// Cage-synchronous average, rate refinement, slot configurations.
#include "identify/cage_average.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "core/constants.h"
#include "identify/count_fit.h"
#include "identify/line_dft.h"

namespace spallkit::identify {
namespace {

// A known cage-periodic signal plus white noise: the average recovers it within its own
// standard errors, and those match the noise (std / sqrt(samples per bin)) within 30 %.
TEST(CageAverage, RecoversAPeriodicSignalWithHonestErrors) {
  const double rate = 4000.0, fc = 8.0, noise = 0.5;
  const int n = 8000, bins = 36;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, noise);
  std::vector<double> x(n);
  auto f = [&](double phase) { return 1.0 + std::cos(phase) + 0.5 * std::sin(3 * phase); };
  for (int i = 0; i < n; ++i) x[i] = f(2.0 * kPi * fc * i / rate) + g(rng);
  const CageAverage a = AverageOverCage(x, rate, fc, bins);
  EXPECT_EQ(a.whole_revolutions, 16);
  int outside = 0;
  for (int b = 0; b < bins; ++b) {
    // The bin average of f over the bin (f varies within a 10 deg bin by ~ its slope).
    double truth = 0.0;
    for (int s = 0; s < 100; ++s) truth += f((b + (s + 0.5) / 100.0) * 2.0 * kPi / bins) / 100.0;
    if (std::abs(a.mean[b] - truth) > 3.0 * a.sigma[b]) ++outside;
    const double expected = noise / std::sqrt(static_cast<double>(n) / bins);
    EXPECT_NEAR(a.sigma[b], expected, 0.3 * expected);
  }
  EXPECT_LE(outside, 2);  // of 36 bins at 3 sigma, with sigma itself from 16 revolutions
}

TEST(RefineRate, FindsALineBetweenBins) {
  const double rate = 2000.0, f = 8.2773;
  std::vector<double> x(2000);  // 1 s: bins of 1 Hz
  for (size_t i = 0; i < x.size(); ++i)
    x[i] = std::cos(2.0 * kPi * f * i / rate) + 0.5 * std::cos(2.0 * kPi * 2 * f * i / rate + 1);
  // Within 1 % of a bin (the mirror line at -f and the harmonic leak a little into the peak).
  EXPECT_NEAR(RefineRate(x, rate, 8.3, 0.5), f, 0.01);
}

TEST(SlotConfigurations, CountsNecklacesWithSlotZero) {
  EXPECT_EQ(SlotConfigurations(13, 1).size(), 1u);
  EXPECT_EQ(SlotConfigurations(13, 2).size(), 6u);   // {0,s} ~ {0,13-s}
  EXPECT_EQ(SlotConfigurations(13, 3).size(), 22u);  // C(12,2) / 3
  EXPECT_EQ(SlotConfigurations(13, 13).size(), 1u);
  for (const auto& c : SlotConfigurations(13, 3)) {
    EXPECT_EQ(c.front(), 0);
    EXPECT_EQ(CanonicalSlots(c, 13), c);
  }
  // Rotations of a set have one canonical form: the smallest arc.
  EXPECT_EQ(CanonicalSlots({3, 7}, 13), (std::vector<int>{0, 4}));
  EXPECT_EQ(CanonicalSlots({0, 9}, 13), (std::vector<int>{0, 4}));
  EXPECT_EQ(CanonicalSlots({5, 8, 12}, 13), (std::vector<int>{0, 3, 7}));
}

}  // namespace
}  // namespace spallkit::identify
