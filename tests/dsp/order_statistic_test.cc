// SelectKth against std::nth_element: random data, heavy ties, sorted and reversed input, every
// size around the vector width and the small-array cut-over; the sliding variant against it.
#include "dsp/order_statistic.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace spallkit::dsp {
namespace {

double Reference(std::vector<double> v, int k) {
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

TEST(OrderStatisticTest, SelectKthEqualsNthElement) {
  std::mt19937_64 rng(5);
  std::exponential_distribution<double> expo(1.0);
  std::uniform_int_distribution<int> small_int(0, 3);
  for (int n : {1, 2, 7, 8, 9, 16, 17, 31, 401, 1000, 100003}) {
    for (int kind = 0; kind < 4; ++kind) {
      std::vector<double> v(n);
      for (double& e : v) e = kind == 1 ? small_int(rng) : expo(rng);  // kind 1: heavy ties
      if (kind == 2) std::sort(v.begin(), v.end());
      if (kind == 3) std::sort(v.rbegin(), v.rend());
      const std::vector<double> copy = v;
      for (int k : {0, n / 4, n / 2, n - 1}) {
        EXPECT_EQ(SelectKth(v, k), Reference(v, k)) << "n " << n << " kind " << kind << " k " << k;
      }
      EXPECT_EQ(v, copy);  // the input is not modified
    }
  }
}

TEST(OrderStatisticTest, AllEqualValues) {
  const std::vector<double> v(1000, 2.5);
  EXPECT_EQ(SelectKth(v, 500), 2.5);
  EXPECT_EQ(SelectKth(v, 0), 2.5);
}

// A running median's windows (step w / 6, as the noise floor's) over spectra whose answer moves
// slowly (noise), jumps (a step in the level, a strong line), sits on ties, or is zero: every
// window's answer equals SelectKth's, whichever path found it.
TEST(OrderStatisticTest, SlidingSelectKthEqualsSelectKthOnEveryWindow) {
  std::mt19937_64 rng(9);
  std::exponential_distribution<double> expo(1.0);
  std::uniform_int_distribution<int> small_int(0, 3);
  const int n = 20000;
  for (int kind = 0; kind < 5; ++kind) {
    std::vector<double> v(n);
    for (int i = 0; i < n; ++i) {
      switch (kind) {
        case 0:
          v[i] = expo(rng);
          break;  // flat noise floor
        case 1:
          v[i] = expo(rng) * std::exp(-i / 3000.0);
          break;  // falling floor
        case 2:
          v[i] = expo(rng) * (i < n / 2 ? 1.0 : 1000.0);
          break;  // a step
        case 3:
          v[i] = small_int(rng);
          break;  // heavy ties
        default:
          v[i] = i % 97 < 60 ? 0.0 : expo(rng);
          break;  // mostly zero
      }
    }
    if (kind == 0)
      for (int i = 500; i < n; i += 1000) v[i] = 1e6;  // strong lines
    for (int w : {9, 64, 401}) {
      std::vector<int> starts;
      for (int s = 0; s + w <= n; s += std::max(1, w / 6)) starts.push_back(s);
      for (int k : {0, w / 2, w - 1}) {
        std::vector<double> out(starts.size());
        SlidingSelectKth(v.data(), starts, w, k, out);
        for (size_t a = 0; a < starts.size(); ++a) {
          const std::vector<double> window(v.begin() + starts[a], v.begin() + starts[a] + w);
          ASSERT_EQ(out[a], SelectKth(window, k))
              << "kind " << kind << " w " << w << " k " << k << " window " << a;
        }
      }
    }
  }
}

}  // namespace
}  // namespace spallkit::dsp
