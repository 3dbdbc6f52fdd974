#include "dsp/fft.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

namespace {

using spallkit::dsp::ComplexFft;
using spallkit::dsp::FftFriendlySize;
using spallkit::dsp::RealFft;
using cd = std::complex<double>;

std::vector<cd> NaiveDft(const std::vector<cd>& x, int sign) {
  const int n = static_cast<int>(x.size());
  std::vector<cd> out(n);
  for (int k = 0; k < n; ++k) {
    cd sum = 0;
    for (int t = 0; t < n; ++t) {
      sum += x[t] * std::polar(1.0, sign * 2 * std::numbers::pi * double(k) * t / n);
    }
    out[k] = sum;
  }
  return out;
}

std::vector<double> RandomReal(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::vector<double> x(n);
  for (double& v : x) v = g(rng);
  return x;
}

class RealFftSizes : public ::testing::TestWithParam<int> {};

TEST_P(RealFftSizes, ForwardMatchesNaiveDftAndInverseRoundTrips) {
  const int n = GetParam();
  const auto x = RandomReal(n, 7 + n);
  RealFft fft(n);
  ASSERT_EQ(fft.size(), n);
  ASSERT_EQ(fft.bins(), n / 2 + 1);
  std::vector<cd> spec(fft.bins());
  fft.Forward(x.data(), spec.data());
  const auto ref = NaiveDft(std::vector<cd>(x.begin(), x.end()), -1);
  for (int k = 0; k < fft.bins(); ++k) EXPECT_LT(std::abs(spec[k] - ref[k]), 1e-9 * n) << k;
  std::vector<double> back(n);
  fft.Inverse(spec.data(), back.data());
  for (int t = 0; t < n; ++t) EXPECT_NEAR(back[t] / n, x[t], 1e-12) << t;
}

INSTANTIATE_TEST_SUITE_P(EvenAndOdd, RealFftSizes, ::testing::Values(1, 2, 45, 60, 97, 128));

// Arrays that do not have FFTW's SIMD alignment go through the scratch copy and give the same.
TEST(RealFft, MisalignedArraysGiveTheSameResult) {
  const int n = 96;
  const auto x = RandomReal(n + 1, 3);
  RealFft fft(n);
  std::vector<cd> a(n / 2 + 1), b(n / 2 + 2);
  fft.Forward(x.data(), a.data());
  std::vector<double> shifted(x.begin(), x.begin() + n);
  shifted.insert(shifted.begin(), 0.0);  // data() + 1 is misaligned by one double
  fft.Forward(shifted.data() + 1, b.data());
  for (int k = 0; k <= n / 2; ++k) EXPECT_LT(std::abs(a[k] - b[k]), 1e-12);
}

TEST(RealFft, CosineLandsInItsBinWithAmplitudeTimesNOverTwo) {
  const int n = 480;
  const double amplitude = 2.5;
  std::vector<double> x(n);
  for (int t = 0; t < n; ++t) x[t] = amplitude * std::cos(2 * std::numbers::pi * 37 * t / n);
  RealFft fft(n);
  std::vector<cd> spec(fft.bins());
  fft.Forward(x.data(), spec.data());
  for (int k = 0; k < fft.bins(); ++k) {
    EXPECT_NEAR(std::abs(spec[k]), k == 37 ? amplitude * n / 2 : 0.0, 1e-9) << k;
  }
}

TEST(ComplexFft, BothSignsBatchedAndInPlaceMatchNaiveDft) {
  const int n = 30, howmany = 3;
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  std::vector<cd> x(n * howmany);
  for (auto& v : x) v = cd(g(rng), g(rng));
  for (int sign : {-1, +1}) {
    ComplexFft fft(n, sign, howmany);
    std::vector<cd> out(n * howmany);
    fft.Execute(x.data(), out.data());
    std::vector<cd> inplace = x;
    fft.Execute(inplace.data(), inplace.data());
    for (int b = 0; b < howmany; ++b) {
      const auto ref = NaiveDft(std::vector<cd>(x.begin() + b * n, x.begin() + (b + 1) * n), sign);
      for (int k = 0; k < n; ++k) {
        EXPECT_LT(std::abs(out[b * n + k] - ref[k]), 1e-10);
        EXPECT_LT(std::abs(inplace[b * n + k] - ref[k]), 1e-10);
      }
    }
  }
}

TEST(ComplexFft, InputIsPreservedOutOfPlace) {
  const int n = 64;
  std::vector<cd> x(n);
  for (int i = 0; i < n; ++i) x[i] = cd(i, -i);
  const auto copy = x;
  std::vector<cd> out(n);
  ComplexFft fft(n, -1);
  fft.Execute(x.data(), out.data());
  EXPECT_EQ(x, copy);
}

TEST(ComplexFftF, MatchesNaiveDftToSinglePrecision) {
  const int n = 60;
  std::mt19937 rng(4);
  std::normal_distribution<double> g;
  std::vector<cd> x(n);
  for (auto& v : x) v = cd(g(rng), g(rng));
  auto in = spallkit::dsp::AllocateComplexF(n);
  auto out = spallkit::dsp::AllocateComplexF(n);
  for (int i = 0; i < n; ++i) in[i] = std::complex<float>(x[i]);
  spallkit::dsp::ComplexFftF fft(n, +1);
  EXPECT_EQ(fft.size(), n);
  fft.Execute(in.get(), out.get());
  const auto ref = NaiveDft(x, +1);
  for (int k = 0; k < n; ++k) EXPECT_LT(std::abs(cd(out[k]) - ref[k]), 1e-5 * n) << k;
}

TEST(FftFriendlySize, SmallestSevenSmoothSizeNotBelowN) {
  EXPECT_EQ(FftFriendlySize(1), 1);
  EXPECT_EQ(FftFriendlySize(11), 12);
  EXPECT_EQ(FftFriendlySize(13), 14);
  EXPECT_EQ(FftFriendlySize(97), 98);
  EXPECT_EQ(FftFriendlySize(1024), 1024);
  const int m = FftFriendlySize(480001);
  EXPECT_GE(m, 480001);
  int r = m;
  for (int p : {2, 3, 5, 7}) {
    while (r % p == 0) r /= p;
  }
  EXPECT_EQ(r, 1);
  for (int k = 480001; k < m; ++k) {
    int q = k;
    for (int p : {2, 3, 5, 7}) {
      while (q % p == 0) q /= p;
    }
    EXPECT_NE(q, 1) << k;
  }
}

TEST(FftFastSize, SmallestSevenSmoothMultipleOf64) {
  EXPECT_EQ(spallkit::dsp::FftFastSize(1), 64);
  EXPECT_EQ(spallkit::dsp::FftFastSize(64), 64);
  EXPECT_EQ(spallkit::dsp::FftFastSize(65), 128);
  EXPECT_EQ(spallkit::dsp::FftFastSize(60025), 60480);  // 2^6 3^3 5 7
  EXPECT_EQ(spallkit::dsp::FftFastSize(704), 768);      // 704 = 2^6 11 is not 7-smooth
}

}  // namespace
