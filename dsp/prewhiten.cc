#include "dsp/prewhiten.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/multiversion.h"
#include "dsp/fft.h"

namespace spallkit::dsp {

// Two passes that vectorise (multi-versioned, core/multiversion.h): |X_k| as sqrt(|X_k|^2), not
// std::abs (a hypot call per bin), and a multiplication by 1/|X_k|.
SPALLKIT_MULTIVERSION
void WhitenSpectrum(std::span<std::complex<double>> spectrum, int n) {
  SPALLKIT_CHECK(static_cast<int>(spectrum.size()) == n / 2 + 1,
                 "WhitenSpectrum: " << spectrum.size() << " bins for n = " << n);
  const size_t bins = spectrum.size();
  double* v = reinterpret_cast<double*>(spectrum.data());
  // Bins 1.. of the one-sided spectrum; the Nyquist bin (even n) counts once, the others twice.
  const size_t last = (2 * (bins - 1) == static_cast<size_t>(n)) ? bins - 1 : bins;
  // RMS about the mean, by Parseval over the two-sided spectrum (bin 0 excluded).
  double energy = 0, max_power = 0;
  for (size_t k = 1; k < last; ++k) {
    const double p = v[2 * k] * v[2 * k] + v[2 * k + 1] * v[2 * k + 1];
    energy += 2 * p;
    max_power = p > max_power ? p : max_power;
  }
  for (size_t k = last; k < bins; ++k) {
    const double p = v[2 * k] * v[2 * k] + v[2 * k + 1] * v[2 * k + 1];
    energy += p;
    max_power = std::max(max_power, p);
  }
  const double rms = std::sqrt(energy) / n;
  const double floor = 1e-12 * std::sqrt(max_power);
  long kept = 0;  // two-sided count of unit bins
  v[0] = v[1] = 0.0;
  for (size_t k = 1; k < bins; ++k) {
    const double mag = std::sqrt(v[2 * k] * v[2 * k] + v[2 * k + 1] * v[2 * k + 1]);
    const bool unit = mag > floor && mag != 0;
    const double inv = unit ? 1.0 / mag : 0.0;
    v[2 * k] *= inv;
    v[2 * k + 1] *= inv;
    kept += unit ? (k < last ? 2 : 1) : 0;
  }
  // Unit bins give a record of RMS sqrt(kept) / n (Parseval); scale it to `rms`.
  const double scale = kept > 0 ? rms * n / std::sqrt(static_cast<double>(kept)) : 0.0;
  for (size_t j = 0; j < 2 * bins; ++j) v[j] *= scale;
}

std::vector<double> CepstrumPrewhiten(std::span<const double> x) {
  if (x.size() < 8) {
    std::ostringstream os;
    os << "cepstrum pre-whitening: record has " << x.size() << " samples, at least 8 expected";
    throw InputError(os.str());
  }
  if (x.size() > static_cast<size_t>(1) << 30) {
    throw InputError("cepstrum pre-whitening: record longer than 2^30 samples");
  }
  const int n = static_cast<int>(x.size());
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) {
      std::ostringstream os;
      os << "cepstrum pre-whitening: sample " << i << " is not finite (" << x[i] << ")";
      throw InputError(os.str());
    }
  }
  RealFft fft(n);
  std::vector<std::complex<double>> spec(fft.bins());
  fft.Forward(x.data(), spec.data());
  WhitenSpectrum(spec, n);
  std::vector<double> out(n);
  fft.Inverse(spec.data(), out.data());
  for (double& v : out) v /= n;
  return out;
}

}  // namespace spallkit::dsp
