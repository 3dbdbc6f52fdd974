// SelectKth against std::nth_element: random data, heavy ties, sorted and reversed input, every
// size around the vector width and the small-array cut-over.
#include "dsp/order_statistic.h"

#include <gtest/gtest.h>

#include <algorithm>
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

}  // namespace
}  // namespace spallkit::dsp
