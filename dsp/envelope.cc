#include "dsp/envelope.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "dsp/prewhiten.h"

namespace spallkit::dsp {

// Plans and scratch for one decimated size m, reused by every band that resolves to m.
struct EnvelopeAnalyzer::Plans {
  explicit Plans(int m) : inverse(m, +1), real(m), envelope(m), se(m), se_spectrum(m / 2 + 1) {}
  ComplexFft inverse;  // shifted band bins -> complex envelope
  RealFft real;        // squared envelope -> SES
  std::vector<std::complex<double>> envelope;
  std::vector<double> se;
  std::vector<std::complex<double>> se_spectrum;
};

namespace {

void CheckSamples(std::span<const double> x, int min_samples, const char* what) {
  if (static_cast<long long>(x.size()) < min_samples) {
    std::ostringstream os;
    os << what << ": record has " << x.size() << " samples, at least " << min_samples
       << " expected";
    throw InputError(os.str());
  }
  for (size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) {
      std::ostringstream os;
      os << what << ": sample " << i << " is not finite (" << x[i] << ")";
      throw InputError(os.str());
    }
  }
}

}  // namespace

EnvelopeAnalyzer::EnvelopeAnalyzer(std::span<const double> x, double fs_hz) {
  if (!(fs_hz > 0) || !std::isfinite(fs_hz)) {
    std::ostringstream os;
    os << "envelope analysis: sample rate must be > 0 Hz, got " << fs_hz;
    throw InputError(os.str());
  }
  CheckSamples(x, kMinSamples, "envelope analysis");
  if (x.size() > static_cast<size_t>(1) << 30) {
    throw InputError("envelope analysis: record longer than 2^30 samples");
  }
  n_ = static_cast<int>(x.size());
  fs_hz_ = fs_hz;
  spectrum_.resize(n_ / 2 + 1);
  RealFft fft(n_);
  fft.Forward(x.data(), spectrum_.data());
  spectrum_[0] = 0.0;  // removes the mean
}

EnvelopeAnalyzer::~EnvelopeAnalyzer() = default;
EnvelopeAnalyzer::EnvelopeAnalyzer(EnvelopeAnalyzer&&) noexcept = default;
EnvelopeAnalyzer& EnvelopeAnalyzer::operator=(EnvelopeAnalyzer&&) noexcept = default;

EnvelopeAnalyzer EnvelopeAnalyzer::Prewhitened(std::span<const double> x, double fs_hz) {
  EnvelopeAnalyzer analyzer(x, fs_hz);
  WhitenSpectrum(analyzer.spectrum_, analyzer.n_);
  return analyzer;
}

EnvelopeAnalyzer::BandBins EnvelopeAnalyzer::Resolve(const Band& band, double max_alpha_hz) const {
  const double nyquist = 0.5 * fs_hz_;
  if (!std::isfinite(band.low_hz) || !std::isfinite(band.high_hz) || band.low_hz < 0 ||
      band.high_hz > nyquist * (1 + 1e-12) || band.low_hz >= band.high_hz) {
    std::ostringstream os;
    os << "envelope band [" << band.low_hz << ", " << band.high_hz
       << "] Hz: expected 0 <= low < high <= fs/2 = " << nyquist << " Hz";
    throw InputError(os.str());
  }
  if (!(max_alpha_hz >= 0) || !std::isfinite(max_alpha_hz)) {
    std::ostringstream os;
    os << "envelope max_alpha_hz must be >= 0, got " << max_alpha_hz;
    throw InputError(os.str());
  }
  const double df = fs_hz_ / n_;
  BandBins b;
  b.k1 = std::max(0, static_cast<int>(std::ceil(band.low_hz / df - 1e-9)));
  b.k2 = std::min(n_ / 2, static_cast<int>(std::floor(band.high_hz / df + 1e-9)));
  if (b.k2 < b.k1) {
    std::ostringstream os;
    os << "envelope band [" << band.low_hz << ", " << band.high_hz
       << "] Hz holds no FFT bin (resolution " << df << " Hz)";
    throw InputError(os.str());
  }
  const int nb = b.k2 - b.k1 + 1;
  if (max_alpha_hz > 0) {
    // Beyond fs/2 there is nothing to resolve: the full-rate SE itself stops there.
    b.alpha_bins = static_cast<int>(std::floor(std::min(max_alpha_hz, nyquist) / df + 1e-9));
  } else {
    b.alpha_bins = nb - 1;  // the squared envelope spans +-(k2-k1) bins
  }
  // |c|^2 images start at m - (nb - 1): keep them above alpha; and alpha must be below m/2.
  b.m = FftFastSize(std::max({nb + b.alpha_bins, 2 * b.alpha_bins + 2, 8}));
  return b;
}

EnvelopeAnalyzer::Plans& EnvelopeAnalyzer::PlansFor(int m) {
  auto& slot = plans_[m];
  if (!slot) slot = std::make_unique<Plans>(m);
  return *slot;
}

void EnvelopeAnalyzer::FillEnvelope(const BandBins& b) {
  Plans& p = PlansFor(b.m);
  auto& c = p.envelope;
  // Analytic-signal weights: 2 for positive frequencies, 1 for DC and Nyquist; 1/N undoes the
  // unnormalised forward FFT, so a sine of amplitude A in the band gives |c| = A.
  const double scale = 2.0 / n_;
  const int nb = b.k2 - b.k1 + 1;
  for (int j = 0; j < nb; ++j) {
    const int k = b.k1 + j;
    const bool edge = (k == 0) || (2 * k == n_);
    c[j] = spectrum_[k] * (edge ? 0.5 * scale : scale);
  }
  std::fill(c.begin() + nb, c.end(), std::complex<double>(0.0));
  p.inverse.Execute(c.data(), c.data());
}

EnvelopeSpectrum EnvelopeAnalyzer::Compute(const Band& band, const EnvelopeOptions& options) {
  const BandBins b = Resolve(band, options.max_alpha_hz);
  FillEnvelope(b);
  Plans& p = PlansFor(b.m);
  const int m = b.m;
  double sum = 0;
  if (options.squared) {
    for (int i = 0; i < m; ++i) {
      p.se[i] = std::norm(p.envelope[i]);
      sum += p.se[i];
    }
  } else {
    for (int i = 0; i < m; ++i) {
      p.se[i] = std::abs(p.envelope[i]);
      sum += p.se[i];
    }
  }
  const double mean = sum / m;
  for (int i = 0; i < m; ++i) p.se[i] -= mean;
  p.real.Forward(p.se.data(), p.se_spectrum.data());

  EnvelopeSpectrum out;
  const double df = fs_hz_ / n_;
  out.resolution_hz = df;
  out.band = band;
  out.squared = options.squared;
  out.envelope_rate_hz = m * df;
  out.freq_hz.resize(b.alpha_bins + 1);
  out.level.resize(b.alpha_bins + 1);
  const double inv_m = 1.0 / m;
  for (int k = 0; k <= b.alpha_bins; ++k) {
    out.freq_hz[k] = k * df;
    out.level[k] = std::abs(p.se_spectrum[k]) * inv_m;
  }
  out.level[0] = 0.0;  // mean removed; avoids a rounding residue
  return out;
}

std::vector<double> EnvelopeAnalyzer::SquaredEnvelope(const Band& band,
                                                      double max_alpha_hz,
                                                      double* rate_hz) {
  const BandBins b = Resolve(band, max_alpha_hz);
  FillEnvelope(b);
  const auto& c = PlansFor(b.m).envelope;
  std::vector<double> se(b.m);
  for (int i = 0; i < b.m; ++i) se[i] = std::norm(c[i]);
  if (rate_hz) *rate_hz = b.m * fs_hz_ / n_;
  return se;
}

double EnvelopeAnalyzer::ComplexEnvelope(const Band& band,
                                         double max_alpha_hz,
                                         std::vector<std::complex<double>>* out) {
  const BandBins b = Resolve(band, max_alpha_hz);
  FillEnvelope(b);
  *out = PlansFor(b.m).envelope;
  return b.m * fs_hz_ / n_;
}

EnvelopeSpectrum SquaredEnvelopeSpectrum(std::span<const double> x,
                                         double fs_hz,
                                         const Band& band,
                                         const EnvelopeOptions& options) {
  EnvelopeAnalyzer analyzer(x, fs_hz);
  return analyzer.Compute(band, options);
}

}  // namespace spallkit::dsp
