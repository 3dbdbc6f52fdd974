// Fault families and faultBandMetrics-style metrics against analytic positions.
#include "dsp/fault_bands.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace spallkit::dsp {
namespace {

TEST(FaultBands, FamiliesFollowKinematicsAndConventions) {
  const auto f = ComputeFrequencies(CatalogBearing("N205EM"), 20.0);
  const auto fams = MakeFaultFamilies(f, {.harmonics = 3});
  ASSERT_EQ(fams.size(), 4u);
  EXPECT_EQ(fams[0].lines.size(), 3u);                // outer: harmonics only
  EXPECT_EQ(fams[1].lines.size(), 9u);                // inner: +/- f_r
  EXPECT_EQ(fams[2].lines.size(), 12u);               // rolling element: the spin series, +/- f_c
  EXPECT_NEAR(fams[2].fundamental_hz, 115.08, 0.01);  // f_b = 2 x BSF (paper)
  // The spin series (k - 1/2) f_b = 1, 3, 5 x BSF after the harmonics, without sidebands.
  EXPECT_TRUE(fams[2].lines[3].half_order);
  EXPECT_EQ(fams[2].lines[3].label, "0.5xf_b");
  EXPECT_NEAR(fams[2].lines[4].nominal_hz, 3.0 * f.roller_spin_hz, 1e-9);
  EXPECT_DOUBLE_EQ(fams[2].lines[5].order(), 2.5);
  EXPECT_EQ(
      MakeFaultFamilies(f, {.harmonics = 3, .rolling_element_spin_series = false})[2].lines.size(),
      9u);
  EXPECT_NEAR(fams[1].lines[5].nominal_hz, 2 * f.bpfi_hz - f.shaft_hz, 1e-9);
  EXPECT_EQ(fams[1].lines[5].label, "2xBPFI-f_r");
  EXPECT_STREQ(ComponentName(fams[3].component), "cage");
  EXPECT_THROW(MakeFaultFamilies(f, {.harmonics = 0}), InputError);
}

TEST(FaultBands, MetricsFindPeaksWithinTolerance) {
  const double df = 0.25;
  std::vector<double> level(4000, 1.0);
  const auto f = ComputeFrequencies(CatalogBearing("6205"), 30.0);
  // Lines 1 % above kinematics, spread over two bins (true position between them).
  const double true_hz = f.bpfo_hz * 1.01;
  for (int k = 1; k <= 3; ++k) {
    const double pos = k * true_hz / df;
    const int i = static_cast<int>(std::floor(pos));
    const double frac = pos - i;
    // Gaussian-shaped peak sampled at the bins: interpolation is exact.
    for (int j = i - 2; j <= i + 3; ++j)
      level[j] += 100.0 * std::exp(-0.5 * std::pow((j - pos) / 0.8, 2));
    (void)frac;
  }
  const auto m = ComputeFaultBandMetrics(level, df, MakeFaultFamilies(f, {.harmonics = 3}), 0.02);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(m[0].lines[k].peak_hz, (k + 1) * true_hz, 0.01 * df);
    EXPECT_GT(m[0].lines[k].peak_level, 50.0);
  }
  // With 0.5 % tolerance the 1 %-shifted line is outside the window.
  const auto tight =
      ComputeFaultBandMetrics(level, df, MakeFaultFamilies(f, {.harmonics = 3}), 0.005);
  EXPECT_LT(tight[0].lines[0].peak_level, 50.0);
}

}  // namespace
}  // namespace spallkit::dsp
