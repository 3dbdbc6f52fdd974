#include "identify/smooth_envelope.h"

#include <cmath>
#include <complex>

#include "core/constants.h"
#include "core/error.h"
#include "dsp/fft.h"

namespace spallkit::identify {

std::vector<double> SmoothBandSquaredEnvelope(std::span<const double> x,
                                              double fs_hz,
                                              double low_hz,
                                              double high_hz) {
  if (!(low_hz >= 0 && high_hz > low_hz && high_hz <= 0.5 * fs_hz))
    throw InputError("smooth band: need 0 <= low < high <= fs/2 (got " + std::to_string(low_hz) +
                     "-" + std::to_string(high_hz) + " Hz at fs " + std::to_string(fs_hz) + ")");
  const int n = static_cast<int>(x.size());
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= std::max(1, n);
  std::vector<std::complex<double>> buf(n);
  for (int i = 0; i < n; ++i) buf[i] = x[i] - mean;
  dsp::ComplexFft forward(n, -1), inverse(n, +1);
  forward.Execute(buf.data(), buf.data());
  // One-sided, doubled (analytic signal), Hann-weighted over the band; 1/n for the round trip.
  for (int k = 0; k < n; ++k) {
    const double f = (k <= n / 2 ? k : k - n) * fs_hz / n;
    double w = 0.0;
    if (f > low_hz && f < high_hz) {
      const double u = (f - low_hz) / (high_hz - low_hz);
      w = 2.0 * std::sin(kPi * u) * std::sin(kPi * u) / n;
    }
    buf[k] *= w;
  }
  inverse.Execute(buf.data(), buf.data());
  std::vector<double> se(n);
  for (int i = 0; i < n; ++i) se[i] = std::norm(buf[i]);
  return se;
}

}  // namespace spallkit::identify
