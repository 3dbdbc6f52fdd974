// NormalizeSpectrum's floor at its anchor bins is exactly the window median / ln 2 (the fast
// selection must return the same order statistic as std::nth_element), with ties, constant and
// exponential spectra.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <random>
#include <vector>

#include "dsp/detection.h"

namespace spallkit::dsp {
namespace {

// floor[i] at every anchor bin i = 1 + j * (w / 6), from a plain nth_element over its window.
void ExpectExactAnchors(const std::vector<double>& power, int w) {
  DetectionOptions o;
  o.floor_window_bins = w;
  const NormalizedSpectrum s = NormalizeSpectrum(power, 0.1, o);
  const int n = static_cast<int>(power.size());
  const int step = std::max(1, w / 6);
  int checked = 0;
  for (int i = 1; i < n; i += step) {
    const int start = std::clamp(i - w / 2, 1, n - w);
    std::vector<double> window(power.begin() + start, power.begin() + start + w);
    std::nth_element(window.begin(), window.begin() + w / 2, window.end());
    EXPECT_EQ(s.floor[i], window[w / 2] / std::numbers::ln2) << "bin " << i;
    EXPECT_EQ(s.z[i], power[i] / s.floor[i]) << "bin " << i;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

TEST(DetectionFloor, ExponentialSpectrumAnchorsAreExactMedians) {
  std::mt19937_64 rng(3);
  std::exponential_distribution<double> e(1.0);
  for (int w : {21, 101, 401, 1001}) {
    std::vector<double> p(20000);
    for (double& v : p) v = e(rng);
    ExpectExactAnchors(p, w);
  }
}

TEST(DetectionFloor, TiesAndConstantSpectra) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> level(1, 3);
  std::vector<double> ties(5000);
  for (double& v : ties) v = level(rng);
  ExpectExactAnchors(ties, 401);
  std::vector<double> constant(3000, 2.5);
  ExpectExactAnchors(constant, 401);
  const NormalizedSpectrum s = NormalizeSpectrum(constant, 0.1);
  for (size_t i = 1; i < constant.size(); ++i)
    ASSERT_DOUBLE_EQ(s.floor[i], 2.5 / std::numbers::ln2);
}

// With a shape, the floor is that of power / shape, multiplied back, and z is (power / shape)
// divided by the flat floor: the same numbers as normalising the flattened spectrum by hand.
TEST(DetectionFloor, ShapedFloorIsTheFlattenedSpectrumsFloorTimesTheShape) {
  std::mt19937_64 rng(7);
  std::exponential_distribution<double> e(1.0);
  const int n = 8000;
  std::vector<double> power(n), shape(n), flat(n);
  for (int i = 0; i < n; ++i) {
    shape[i] = std::max(0.1, 1.0 - i * 0.1 / 1000.0);  // a band SES's triangle, 1000 Hz band
    power[i] = e(rng) * shape[i];
    flat[i] = power[i] / shape[i];
  }
  const NormalizedSpectrum by_hand = NormalizeSpectrumWindow(flat, 0.1, 401);
  const NormalizedSpectrum shaped = NormalizeSpectrumWindow(power, 0.1, 401, shape);
  ASSERT_EQ(shaped.power, power);
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(shaped.floor[i], by_hand.floor[i] * shape[i]) << i;
    ASSERT_EQ(shaped.z[i], by_hand.z[i]) << i;
  }
  EXPECT_EQ(shaped.effective_samples, by_hand.effective_samples);
}

}  // namespace
}  // namespace spallkit::dsp
