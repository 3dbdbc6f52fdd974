// Synthetic signals with known envelope content, shared by the spectral tests and benchmarks.
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace spallkit::dsp::test_signals {

struct BearingLikeSignal {
  double fs_hz = 48000;
  double seconds = 10;
  double fault_hz = 107.3;      // impulse rate (an outer-race-like line)
  double jitter = 0.01;         // relative random slip of each interval
  double resonance_hz = 9000;   // struck resonance
  double damping_ratio = 0.03;  // of the resonance
  double impulse_amplitude = 1.0;
  double shaft_hz = 29.95;  // deterministic shaft-rate lines (5 harmonics)
  double shaft_amplitude = 0.5;
  double noise_std = 0.3;
  unsigned seed = 1;
};

// Impulses at fault_hz with random spacing jitter, each ringing a single-degree-of-freedom
// resonance, plus shaft harmonics and white Gaussian noise.
inline std::vector<double> MakeBearingLikeSignal(const BearingLikeSignal& s) {
  const int n = static_cast<int>(std::lround(s.fs_hz * s.seconds));
  std::vector<double> x(n, 0.0);
  std::mt19937 rng(s.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double wn = 2 * std::numbers::pi * s.resonance_hz;
  const double decay = s.damping_ratio * wn;
  const int ring = static_cast<int>(std::ceil(8.0 / decay * s.fs_hz));  // e^-8 of the peak
  double t_hit = 0.5 / s.fault_hz;
  while (true) {
    const int i0 = static_cast<int>(std::ceil(t_hit * s.fs_hz));
    if (i0 >= n) break;
    for (int i = i0; i < std::min(n, i0 + ring); ++i) {
      const double t = i / s.fs_hz - t_hit;
      x[i] += s.impulse_amplitude * std::exp(-decay * t) * std::sin(wn * t);
    }
    t_hit += (1.0 + s.jitter * gauss(rng)) / s.fault_hz;
  }
  for (int i = 0; i < n; ++i) {
    const double t = i / s.fs_hz;
    for (int h = 1; h <= 5; ++h) {
      x[i] += s.shaft_amplitude / h * std::cos(2 * std::numbers::pi * h * s.shaft_hz * t + h);
    }
    x[i] += s.noise_std * gauss(rng);
  }
  return x;
}

inline std::vector<double> MakeGaussianNoise(int n, double std_dev, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, std_dev);
  std::vector<double> x(n);
  for (double& v : x) v = gauss(rng);
  return x;
}

// A power spectrum of white noise: independent unit-mean exponential bins (chi-squared with two
// degrees of freedom, scaled), as a periodogram of Gaussian noise has.
inline std::vector<double> NoisePower(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::exponential_distribution<double> e(1.0);
  std::vector<double> p(n);
  for (auto& v : p) v = e(rng);
  return p;
}

// Adds `level` to the bin nearest `hz` of a spectrum with bins df_hz apart.
inline void AddLine(std::vector<double>* power, double hz, double df_hz, double level) {
  (*power)[static_cast<int>(std::lround(hz / df_hz))] += level;
}

}  // namespace spallkit::dsp::test_signals
