#include "dsp/prewhiten.h"

#include <cmath>
#include <complex>
#include <sstream>

#include "core/error.h"
#include "dsp/fft.h"

namespace spallkit::dsp {

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
  double mean = 0;
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) {
      std::ostringstream os;
      os << "cepstrum pre-whitening: sample " << i << " is not finite (" << x[i] << ")";
      throw InputError(os.str());
    }
    mean += x[i];
  }
  mean /= n;
  double var = 0;
  for (int i = 0; i < n; ++i) var += (x[i] - mean) * (x[i] - mean);
  const double rms = std::sqrt(var / n);

  RealFft fft(n);
  std::vector<std::complex<double>> spec(fft.bins());
  fft.Forward(x.data(), spec.data());
  spec[0] = 0.0;  // mean removed
  double max_mag = 0;
  for (const auto& v : spec) max_mag = std::max(max_mag, std::abs(v));
  const double floor = 1e-12 * max_mag;
  // Unit-magnitude bins: sum over the two-sided spectrum of |Y|^2 is (n - 1) (DC zero), so the
  // inverse transform (times n) has RMS sqrt(n - 1); rescale to the input's RMS.
  int kept = 0;
  for (size_t k = 0; k < spec.size(); ++k) {
    const double mag = std::abs(spec[k]);
    if (k == 0 || mag <= floor) {
      spec[k] = 0.0;
    } else {
      spec[k] /= mag;
      kept += (2 * k == static_cast<size_t>(n)) ? 1 : 2;
    }
  }
  std::vector<double> out(n);
  fft.Inverse(spec.data(), out.data());
  const double out_rms = kept > 0 ? std::sqrt(static_cast<double>(kept)) : 1.0;
  const double scale = (kept > 0 && rms > 0) ? rms / out_rms : 0.0;
  for (double& v : out) v *= scale;
  return out;
}

}  // namespace spallkit::dsp
