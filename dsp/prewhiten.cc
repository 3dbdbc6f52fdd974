#include "dsp/prewhiten.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "dsp/fft.h"

namespace spallkit::dsp {

void WhitenSpectrum(std::span<std::complex<double>> spectrum, int n) {
  SPALLKIT_CHECK(static_cast<int>(spectrum.size()) == n / 2 + 1,
                 "WhitenSpectrum: " << spectrum.size() << " bins for n = " << n);
  // RMS about the mean, by Parseval over the two-sided spectrum (bin 0 excluded).
  double energy = 0, max_mag = 0;
  for (size_t k = 1; k < spectrum.size(); ++k) {
    const double p = std::norm(spectrum[k]);
    energy += (2 * k == static_cast<size_t>(n)) ? p : 2 * p;
    max_mag = std::max(max_mag, std::sqrt(p));
  }
  const double rms = std::sqrt(energy) / n;
  const double floor = 1e-12 * max_mag;
  int kept = 0;  // two-sided count of unit bins
  spectrum[0] = 0.0;
  for (size_t k = 1; k < spectrum.size(); ++k) {
    const double mag = std::abs(spectrum[k]);
    if (mag <= floor || mag == 0) {
      spectrum[k] = 0.0;
    } else {
      spectrum[k] /= mag;
      kept += (2 * k == static_cast<size_t>(n)) ? 1 : 2;
    }
  }
  // Unit bins give a record of RMS sqrt(kept) / n (Parseval); scale it to `rms`.
  const double scale = kept > 0 ? rms * n / std::sqrt(static_cast<double>(kept)) : 0.0;
  for (auto& v : spectrum) v *= scale;
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
