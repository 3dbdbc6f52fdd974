#include "dsp/spectra.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/error.h"
#include "tests/dsp/spectral_test_signals.h"

namespace {

using namespace spallkit::dsp;
using spallkit::InputError;

double Integral(const Spectrum& s) {
  double sum = 0;
  for (double p : s.psd) sum += p;
  return sum * s.resolution_hz;
}

// Parseval: the one-sided density of white noise of variance s^2 integrates to s^2, and is flat
// at 2 s^2 / fs.
TEST(WelchPsd, WhiteNoiseIntegratesToItsVariance) {
  const double sigma = 1.7, fs = 5000;
  const auto x = test_signals::MakeGaussianNoise(1 << 17, sigma, 21);
  const auto s = WelchPsd(x, fs, {.segment = 1024, .overlap = 0.5});
  EXPECT_EQ(s.psd.size(), 513u);
  EXPECT_DOUBLE_EQ(s.resolution_hz, fs / 1024);
  EXPECT_EQ(s.segments, 1 + ((1 << 17) - 1024) / 512);
  EXPECT_NEAR(Integral(s), sigma * sigma, 0.02 * sigma * sigma);
  double mean_inner = 0;
  for (size_t k = 1; k + 1 < s.psd.size(); ++k) mean_inner += s.psd[k] / (s.psd.size() - 2);
  EXPECT_NEAR(mean_inner, 2 * sigma * sigma / fs, 0.02 * 2 * sigma * sigma / fs);
}

// A sine of amplitude A lands at its frequency and its peak carries A^2/2.
TEST(WelchPsd, SineLandsAtItsFrequencyWithItsPower) {
  const double fs = 8000, f0 = 1234.5, a = 3.0;
  std::vector<double> x(80000);
  for (size_t i = 0; i < x.size(); ++i) x[i] = a * std::sin(2 * std::numbers::pi * f0 * i / fs);
  const auto s = WelchPsd(x, fs, {.segment = 2048, .overlap = 0.75});
  const size_t peak = std::max_element(s.psd.begin(), s.psd.end()) - s.psd.begin();
  EXPECT_NEAR(s.freq_hz[peak], f0, s.resolution_hz);
  double power = 0;
  for (size_t k = peak - 4; k <= peak + 4; ++k) power += s.psd[k] * s.resolution_hz;
  EXPECT_NEAR(power, a * a / 2, 0.01 * a * a / 2);
  EXPECT_NEAR(Integral(s), a * a / 2, 0.01 * a * a / 2);
}

// A linear chirp 500 -> 3500 Hz over 2 s: the STFT ridge follows the instantaneous frequency.
TEST(Stft, FollowsAChirp) {
  const double fs = 16000, f0 = 500, f1 = 3500, duration = 2;
  const double rate = (f1 - f0) / duration;
  std::vector<double> x(static_cast<size_t>(fs * duration));
  for (size_t i = 0; i < x.size(); ++i) {
    const double t = i / fs;
    x[i] = std::cos(2 * std::numbers::pi * (f0 * t + 0.5 * rate * t * t));
  }
  const auto s = Stft(x, fs, {.window = 512, .hop = 128});
  EXPECT_EQ(s.frames, 1 + (32000 - 512) / 128);
  EXPECT_EQ(s.bins, 257);
  EXPECT_DOUBLE_EQ(s.freq_resolution_hz, fs / 512);
  EXPECT_DOUBLE_EQ(s.time_resolution_s, 128 / fs);
  ASSERT_EQ(s.power_db.size(), static_cast<size_t>(s.frames) * s.bins);
  for (int f = 0; f < s.frames; ++f) {
    int best = 0;
    for (int k = 1; k < s.bins; ++k) {
      if (s.at(f, k) > s.at(f, best)) best = k;
    }
    const double expected = f0 + rate * s.time_s[f];
    EXPECT_NEAR(s.freq_hz[best], expected, s.freq_resolution_hz) << "frame " << f;
  }
  EXPECT_NEAR(s.time_s.front(), 256 / fs, 1e-12);
}

// The STFT frames use the same density scaling as Welch: averaging them gives the same PSD.
TEST(Stft, FramesAverageToWelch) {
  const auto x = test_signals::MakeGaussianNoise(20000, 1.0, 4);
  const auto s = Stft(x, 1000, {.window = 256, .hop = 128});
  const auto w = WelchPsd(x, 1000, {.segment = 256, .overlap = 0.5});
  ASSERT_EQ(s.frames, w.segments);
  for (int k = 0; k < s.bins; ++k) {
    double mean = 0;
    for (int f = 0; f < s.frames; ++f) mean += std::pow(10.0, s.at(f, k) / 10) / s.frames;
    EXPECT_NEAR(mean, w.psd[k], 1e-9 * w.psd[k]) << k;
  }
}

TEST(Spectra, BadInputIsAnInputError) {
  const auto x = test_signals::MakeGaussianNoise(5000, 1.0, 1);
  EXPECT_THROW(WelchPsd(x, 0), InputError);
  EXPECT_THROW(WelchPsd(x, 1000, {.segment = 4}), InputError);
  EXPECT_THROW(WelchPsd(x, 1000, {.segment = 256, .overlap = 1.0}), InputError);
  EXPECT_THROW(WelchPsd(x, 1000, {.segment = 256, .overlap = -0.1}), InputError);
  EXPECT_THROW(WelchPsd(x, 1000, {.segment = 8192}), InputError);  // record shorter
  EXPECT_THROW(Stft(x, -1), InputError);
  EXPECT_THROW(Stft(x, 1000, {.window = 256, .hop = 0}), InputError);
  EXPECT_THROW(Stft(std::span(x).first(100), 1000), InputError);
  auto bad = x;
  bad[3] = INFINITY;
  EXPECT_THROW(WelchPsd(bad, 1000), InputError);
}

}  // namespace
