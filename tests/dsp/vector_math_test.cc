// The vectorisable log and exp of dsp/vector_math.h against libm, in ulp, over their ranges.
#include "dsp/vector_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace spallkit::dsp {
namespace {

// Distance in units in the last place of the reference.
double Ulps(double value, double reference) {
  if (value == reference) return 0.0;
  const double ulp = std::nextafter(std::abs(reference), INFINITY) - std::abs(reference);
  return std::abs(value - reference) / ulp;
}

TEST(VectorMathTest, LogAtLeastOneMatchesLibmWithinTwoUlp) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(0.0, 1000.0);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    // Log-uniform over [1, 2^1000], plus the neighbourhood of 1 and of sqrt(2), where the
    // reduction changes binade.
    double x = std::exp2(exponent(rng));
    if (i % 4 == 1) x = 1.0 + std::ldexp(exponent(rng) / 1000.0, -(i % 60));
    if (i % 4 == 2) x = std::sqrt(2.0) * (1.0 + (exponent(rng) - 500.0) * 1e-12);
    worst = std::max(worst, Ulps(LogAtLeastOne(x), std::log(x)));
  }
  EXPECT_LE(worst, 2.0);
  EXPECT_EQ(LogAtLeastOne(1.0), 0.0);
  EXPECT_NEAR(LogAtLeastOne(0x1p1023), 1023 * std::log(2.0), 1e-12);
}

TEST(VectorMathTest, Log1pNonNegativeMatchesLibmWithinTwoUlp) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> exponent(-80.0, 80.0);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double y = std::exp2(exponent(rng));
    worst = std::max(worst, Ulps(Log1pNonNegative(y), std::log1p(y)));
  }
  EXPECT_LE(worst, 2.0);
  EXPECT_EQ(Log1pNonNegative(0.0), 0.0);
  EXPECT_EQ(Log1pNonNegative(1e-300), 1e-300);  // below the rounding of 1 + y: y itself
}

TEST(VectorMathTest, ExpNonPositiveMatchesLibmWithinTwoUlp) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> x_range(-708.0, 0.0);
  std::uniform_real_distribution<double> small(-1e-3, 0.0);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double x = i % 2 ? x_range(rng) : small(rng);
    worst = std::max(worst, Ulps(ExpNonPositive(x), std::exp(x)));
  }
  EXPECT_LE(worst, 2.0);
  EXPECT_EQ(ExpNonPositive(0.0), 1.0);
  EXPECT_EQ(ExpNonPositive(-1e6), ExpNonPositive(-708.0));  // clamped, no underflow to 0
  EXPECT_GT(ExpNonPositive(-708.0), 0.0);
}

}  // namespace
}  // namespace spallkit::dsp
