#include "core/decimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using spallkit::StreamingDecimator;

namespace {
// Amplitude of a sine of frequency f in x (least squares against sin/cos at the same rate).
double SineAmplitude(const std::vector<double>& x, double f, double fs, int skip) {
  double s = 0, c = 0;
  int n = 0;
  for (size_t i = skip; i < x.size(); ++i, ++n) {
    s += x[i] * std::sin(2 * std::numbers::pi * f * i / fs);
    c += x[i] * std::cos(2 * std::numbers::pi * f * i / fs);
  }
  return 2.0 * std::hypot(s, c) / n;
}
}  // namespace

// A pass-band tone keeps its amplitude and phase alignment; a tone above the output Nyquist
// frequency (which would alias) is suppressed by more than 60 dB.
TEST(StreamingDecimator, PassesInBandAndRejectsAliasingTones) {
  const int factor = 8;
  const double fs_in = 160000.0, fs_out = fs_in / factor;
  for (double f : {1000.0, 5000.0}) {
    StreamingDecimator d(factor);
    std::vector<double> out;
    for (int i = 0; i < 160000; ++i) d.Push(std::sin(2 * std::numbers::pi * f * i / fs_in), &out);
    ASSERT_GT(out.size(), 19000u);
    EXPECT_NEAR(SineAmplitude(out, f, fs_out, 100), 1.0, 2e-3) << f;
    // Output sample k aligns with input sample k * factor (group delay compensated).
    EXPECT_NEAR(out[1000], std::sin(2 * std::numbers::pi * f * 1000 * factor / fs_in), 2e-3);
  }
  StreamingDecimator d(factor);
  std::vector<double> out;
  const double f_alias = 17000.0;  // folds to 3 kHz at 20 kHz
  for (int i = 0; i < 160000; ++i)
    d.Push(std::sin(2 * std::numbers::pi * f_alias * i / fs_in), &out);
  EXPECT_LT(SineAmplitude(out, fs_out - f_alias, fs_out, 100), 1e-3);  // the 3 kHz alias
}

TEST(StreamingDecimator, RestoredStateContinuesIdentically) {
  StreamingDecimator a(4), b(4);
  std::vector<double> out_a, out_b;
  for (int i = 0; i < 1000; ++i) a.Push(std::cos(0.01 * i * i), &out_a);
  const auto state = a.SaveState();
  b.RestoreState(state);
  out_b = out_a;
  for (int i = 1000; i < 2000; ++i) {
    a.Push(std::cos(0.01 * i * i), &out_a);
    b.Push(std::cos(0.01 * i * i), &out_b);
  }
  EXPECT_EQ(out_a, out_b);
}
