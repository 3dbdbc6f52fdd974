// Synthetic bearing-fault records for the diagnosis tests and benchmark: impulse trains at a known
// rate exciting a damped resonance, optional amplitude modulation (load zone at the shaft rate for
// an inner-race fault, at the cage rate for a rolling element), random slip of each interval,
// Gaussian noise, and distractor lines (shaft harmonics, 50 Hz mains harmonics, a BPFO-order line).
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/record_io.h"

namespace spallkit::testing {

struct FaultSignalSpec {
  double fs_hz = 12000.0;
  double duration_s = 2.0;
  double rate_hz = 0.0;          // impulse rate; 0 = no impulses
  double amplitude = 1.0;        // impulse peak
  double resonance_hz = 3000.0;  // excited structural resonance
  double damping_ratio = 0.05;
  double modulation_hz = 0.0;     // amplitude modulation of the impulses
  double modulation_depth = 0.0;  // 0..1: a = 1 - depth + depth * (1 + cos)/2
  double jitter = 0.003;          // std of each interval, relative (random slip)
  // Every other impulse's amplitude relative to the others: a roller spall strikes the outer and
  // the inner race in turn, and the two impacts differ (1: alike, no 1 x BSF series).
  double alternate_ratio = 1.0;
  double noise_rms = 0.3;
  double shaft_hz = 0.0;  // distractor shaft harmonics 1..3 (amplitude shaft_amplitude/k)
  double shaft_amplitude = 0.0;
  double mains_amplitude = 0.0;  // 50, 100, 150, 200 Hz lines
  double extra_line_hz = 0.0;    // e.g. a BPFO-order line of a healthy bearing
  double extra_line_amplitude = 0.0;
  unsigned seed = 1;
};

inline std::vector<double> MakeFaultSignal(const FaultSignalSpec& s) {
  const int n = static_cast<int>(std::lround(s.duration_s * s.fs_hz));
  std::vector<double> x(n, 0.0);
  std::mt19937_64 rng(s.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double two_pi = 2.0 * std::numbers::pi;
  if (s.rate_hz > 0.0) {
    const double wn = two_pi * s.resonance_hz;
    const double zeta = s.damping_ratio;
    const double wd = wn * std::sqrt(1.0 - zeta * zeta);
    const int len = std::min(n, static_cast<int>(std::ceil(8.0 / (zeta * wn) * s.fs_hz)));
    std::vector<double> kernel(len);
    for (int i = 0; i < len; ++i) {
      const double t = i / s.fs_hz;
      kernel[i] = std::exp(-zeta * wn * t) * std::sin(wd * t);
    }
    std::uniform_real_distribution<double> phase(0.0, 1.0);
    double t = phase(rng) / s.rate_hz;
    bool other = false;
    while (t < s.duration_s) {
      const double a = (other ? s.alternate_ratio : 1.0) * s.amplitude *
                       (1.0 - s.modulation_depth +
                        s.modulation_depth * 0.5 * (1.0 + std::cos(two_pi * s.modulation_hz * t)));
      other = !other;
      const int i0 = static_cast<int>(std::lround(t * s.fs_hz));
      for (int i = 0; i < len && i0 + i < n; ++i) x[i0 + i] += a * kernel[i];
      t += (1.0 + s.jitter * gauss(rng)) / s.rate_hz;
    }
  }
  for (int i = 0; i < n; ++i) {
    const double t = i / s.fs_hz;
    double v = s.noise_rms * gauss(rng);
    if (s.shaft_amplitude > 0.0)
      for (int k = 1; k <= 3; ++k)
        v += s.shaft_amplitude / k * std::sin(two_pi * k * s.shaft_hz * t + k);
    if (s.mains_amplitude > 0.0)
      for (int k = 1; k <= 4; ++k)
        v += s.mains_amplitude / k * std::sin(two_pi * 50.0 * k * t + 0.3 * k);
    if (s.extra_line_amplitude > 0.0)
      v += s.extra_line_amplitude * std::sin(two_pi * s.extra_line_hz * t);
    x[i] += v;
  }
  return x;
}

// The signal as a record at its own sample rate, as a reader would return it.
inline spallkit::Record MakeFaultRecord(const FaultSignalSpec& spec) {
  spallkit::Record r;
  r.samples = MakeFaultSignal(spec);
  r.sample_rate_hz = spec.fs_hz;
  r.source = "synthetic";
  return r;
}

}  // namespace spallkit::testing
