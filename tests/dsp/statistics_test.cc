#include "dsp/statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/error.h"
#include "tests/dsp/spectral_test_signals.h"

namespace {

using spallkit::InputError;
using spallkit::dsp::ComputeTimeStatistics;

// Sine over whole periods, sampled at its peaks: rms A/sqrt(2), crest sqrt(2), kurtosis 3/2.
TEST(TimeStatistics, SineHasAnalyticValues) {
  const double a = 2.0;
  std::vector<double> x(1000);
  for (size_t i = 0; i < x.size(); ++i) x[i] = a * std::sin(2 * std::numbers::pi * i / 100.0);
  const auto s = ComputeTimeStatistics(x);
  EXPECT_EQ(s.count, 1000);
  EXPECT_NEAR(s.mean, 0.0, 1e-12);
  EXPECT_NEAR(s.rms, a / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(s.peak, a, 1e-12);
  EXPECT_NEAR(s.crest_factor, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(s.kurtosis, 1.5, 1e-12);
  EXPECT_NEAR(s.skewness, 0.0, 1e-12);
}

// An offset changes mean and rms, not the central moments.
TEST(TimeStatistics, OffsetSineKeepsCentralMoments) {
  const double a = 1.0, c = 3.0;
  std::vector<double> x(400);
  for (size_t i = 0; i < x.size(); ++i) x[i] = c + a * std::cos(2 * std::numbers::pi * i / 40.0);
  const auto s = ComputeTimeStatistics(x);
  EXPECT_NEAR(s.mean, c, 1e-12);
  EXPECT_NEAR(s.rms, std::sqrt(c * c + a * a / 2), 1e-12);
  EXPECT_NEAR(s.peak, c + a, 1e-12);
  EXPECT_NEAR(s.kurtosis, 1.5, 1e-10);
}

TEST(TimeStatistics, SquareWaveHasKurtosisOneAndCrestOne) {
  std::vector<double> x(64);
  for (size_t i = 0; i < x.size(); ++i) x[i] = (i % 8 < 4) ? 0.5 : -0.5;
  const auto s = ComputeTimeStatistics(x);
  EXPECT_NEAR(s.kurtosis, 1.0, 1e-12);
  EXPECT_NEAR(s.crest_factor, 1.0, 1e-12);
}

// Large samples: Gaussian kurtosis 3, skewness 0; uniform kurtosis 9/5; exponential skewness 2,
// kurtosis 9 (tolerances several standard errors).
TEST(TimeStatistics, DistributionsHaveTheirTheoreticalMoments) {
  const int n = 400000;
  const auto g = spallkit::dsp::test_signals::MakeGaussianNoise(n, 2.0, 8);
  const auto sg = ComputeTimeStatistics(g);
  EXPECT_NEAR(sg.kurtosis, 3.0, 0.04);
  EXPECT_NEAR(sg.skewness, 0.0, 0.02);
  EXPECT_NEAR(sg.rms, 2.0, 0.01);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-1, 1);
  std::exponential_distribution<double> expo(1.0);
  std::vector<double> u(n), e(n);
  for (int i = 0; i < n; ++i) {
    u[i] = uni(rng);
    e[i] = expo(rng);
  }
  EXPECT_NEAR(ComputeTimeStatistics(u).kurtosis, 1.8, 0.01);
  const auto se = ComputeTimeStatistics(e);
  EXPECT_NEAR(se.skewness, 2.0, 0.1);
  EXPECT_NEAR(se.kurtosis, 9.0, 0.8);
  EXPECT_NEAR(se.mean, 1.0, 0.01);
}

TEST(TimeStatistics, ConstantRecordAndBadInput) {
  const std::vector<double> c(10, 4.0);
  const auto s = ComputeTimeStatistics(c);
  EXPECT_EQ(s.kurtosis, 0.0);
  EXPECT_EQ(s.skewness, 0.0);
  EXPECT_DOUBLE_EQ(s.crest_factor, 1.0);
  EXPECT_DOUBLE_EQ(s.rms, 4.0);
  const std::vector<double> zeros(5, 0.0);
  EXPECT_EQ(ComputeTimeStatistics(zeros).crest_factor, 0.0);
  EXPECT_THROW(ComputeTimeStatistics(std::vector<double>{}), InputError);
  EXPECT_THROW(ComputeTimeStatistics(std::vector<double>{1.0, NAN}), InputError);
}

}  // namespace
