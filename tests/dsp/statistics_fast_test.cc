// ComputeTimeStatistics' vectorised passes: non-finite samples anywhere (vector body or tail) are
// rejected naming the sample, and the moments match a long-double two-pass reference.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "dsp/statistics.h"

namespace spallkit::dsp {
namespace {

TEST(TimeStatisticsFast, NonFiniteSampleAnywhereIsNamed) {
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  for (double v : bad) {
    for (int at : {0, 5, 50, 96, 100}) {
      std::vector<double> x(101, 0.5);
      x[at] = v;
      try {
        ComputeTimeStatistics(x);
        ADD_FAILURE() << "no error for " << v << " at " << at;
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("sample " + std::to_string(at) + " "),
                  std::string::npos)
            << e.what();
      }
    }
  }
}

TEST(TimeStatisticsFast, MomentsMatchLongDoubleReference) {
  std::mt19937_64 rng(11);
  std::gamma_distribution<double> g(2.0, 1.5);  // skewed, with an offset
  for (int n : {1, 3, 4, 7, 1000, 100003}) {
    std::vector<double> x(n);
    for (double& v : x) v = 1e3 + g(rng);
    long double sum = 0;
    for (double v : x) sum += v;
    const long double mean = sum / n;
    long double m2 = 0, m3 = 0, m4 = 0, peak = 0;
    for (double v : x) {
      const long double d = v - mean;
      m2 += d * d;
      m3 += d * d * d;
      m4 += d * d * d * d;
      peak = std::max(peak, std::abs(static_cast<long double>(v)));
    }
    m2 /= n;
    m3 /= n;
    m4 /= n;
    const TimeStatistics s = ComputeTimeStatistics(x);
    EXPECT_NEAR(s.mean, static_cast<double>(mean), 1e-13 * 1e3) << n;
    EXPECT_EQ(s.peak, static_cast<double>(peak)) << n;
    EXPECT_NEAR(s.rms, static_cast<double>(std::sqrt(m2 + mean * mean)), 1e-12 * 1e3) << n;
    if (n > 3) {
      EXPECT_NEAR(s.kurtosis, static_cast<double>(m4 / (m2 * m2)), 1e-6) << n;
      EXPECT_NEAR(s.skewness, static_cast<double>(m3 / std::pow(m2, 1.5L)), 1e-6) << n;
    }
  }
}

}  // namespace
}  // namespace spallkit::dsp
