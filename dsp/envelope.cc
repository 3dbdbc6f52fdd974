#include "dsp/envelope.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <sstream>

#include "core/error.h"
#include "core/multiversion.h"
#include "dsp/prewhiten.h"
#include "dsp/statistics.h"

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

// Single-precision buffers and plans for one decimated size m (SesPowerFast).
struct EnvelopeAnalyzer::PlansF {
  explicit PlansF(int m)
      : inverse(m, +1),
        half(m / 2, -1),
        bins(AllocateComplexF(m)),
        envelope(AllocateComplexF(m)),
        packed(AllocateComplexF(m / 2)),
        packed_spectrum(AllocateComplexF(m / 2)) {}
  ComplexFftF inverse;  // shifted band bins -> complex envelope
  ComplexFftF half;     // SE packed as m/2 complex values -> their spectrum
  FftwArray<std::complex<float>> bins, envelope, packed, packed_spectrum;
  std::vector<std::complex<double>> twiddle;  // e^{-2 pi i k / m}, k <= the alpha bins used
};

EnvelopeAnalyzer::SesWorkspace::SesWorkspace() = default;
EnvelopeAnalyzer::SesWorkspace::~SesWorkspace() = default;
EnvelopeAnalyzer::SesWorkspace::SesWorkspace(SesWorkspace&&) noexcept = default;
EnvelopeAnalyzer::SesWorkspace& EnvelopeAnalyzer::SesWorkspace::operator=(SesWorkspace&&) noexcept =
    default;

namespace {

// sum v_j (float input, double accumulators) with independent vector accumulators.
double Sum(const float* v, int count) {
  typedef float F8 __attribute__((vector_size(32)));
  typedef double D4 __attribute__((vector_size(32)));
  D4 a = {0, 0, 0, 0}, b = a;
  int j = 0;
  for (; j + 8 <= count; j += 8) {
    F8 x;
    std::memcpy(&x, v + j, sizeof(x));
    a += __builtin_convertvector(__builtin_shufflevector(x, x, 0, 1, 2, 3), D4);
    b += __builtin_convertvector(__builtin_shufflevector(x, x, 4, 5, 6, 7), D4);
  }
  a += b;
  double total = (a[0] + a[1]) + (a[2] + a[3]);
  for (; j < count; ++j) total += v[j];
  return total;
}

void CheckSamples(std::span<const double> x, int min_samples, const char* what) {
  if (static_cast<long long>(x.size()) < min_samples) {
    std::ostringstream os;
    os << what << ": record has " << x.size() << " samples, at least " << min_samples
       << " expected";
    throw InputError(os.str());
  }
  // x - x is 0 for finite samples and NaN otherwise: one vectorisable sum decides whether to
  // look for the bad sample.
  typedef double D4 __attribute__((vector_size(32)));
  D4 check = {0, 0, 0, 0};
  size_t j = 0;
  for (; j + 4 <= x.size(); j += 4) {
    D4 v;
    std::memcpy(&v, x.data() + j, sizeof(v));
    check += v - v;
  }
  double total = (check[0] + check[1]) + (check[2] + check[3]);
  for (; j < x.size(); ++j) total += x[j] - x[j];
  if (total == 0.0) return;
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
  spectrum_ = AllocateComplex(n_ / 2 + 1);
  RealFft fft(n_);
  fft.Forward(x.data(), spectrum_.get());
  spectrum_[0] = 0.0;  // removes the mean
}

EnvelopeAnalyzer::~EnvelopeAnalyzer() = default;
EnvelopeAnalyzer::EnvelopeAnalyzer(EnvelopeAnalyzer&&) noexcept = default;
EnvelopeAnalyzer& EnvelopeAnalyzer::operator=(EnvelopeAnalyzer&&) noexcept = default;

EnvelopeAnalyzer EnvelopeAnalyzer::Prewhitened(std::span<const double> x, double fs_hz) {
  EnvelopeAnalyzer analyzer(x, fs_hz);
  analyzer.Whiten();
  return analyzer;
}

void EnvelopeAnalyzer::Whiten() {
  WhitenSpectrum({spectrum_.get(), static_cast<size_t>(n_ / 2 + 1)}, n_);
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

std::vector<double> EnvelopeAnalyzer::SesPowerFast(const Band& band,
                                                   double max_alpha_hz,
                                                   int* envelope_size) {
  return SesPowerFast(band, max_alpha_hz, envelope_size, &ses_workspace_);
}

std::vector<double> EnvelopeAnalyzer::SesPowerFast(const Band& band,
                                                   double max_alpha_hz,
                                                   int* envelope_size,
                                                   SesWorkspace* workspace) const {
  if (!(max_alpha_hz > 0)) {
    std::ostringstream os;
    os << "envelope SES power: max_alpha_hz must be > 0, got " << max_alpha_hz;
    throw InputError(os.str());
  }
  const BandBins b = Resolve(band, max_alpha_hz);
  const int m = b.m;  // a multiple of 64 (FftFastSize), and > 2 alpha_bins
  if (envelope_size) *envelope_size = m;
  auto& slot = workspace->plans_[m];
  if (!slot) slot = std::make_unique<PlansF>(m);
  PlansF& p = *slot;

  // Band bins with the analytic weights (1, 1/2 at DC and Nyquist), scaled to unit RMS: c_true
  // = gain * c with gain = rms * 2 / n (FillEnvelope's scale), so SE_true = gain^2 SE and
  // P_true = gain^4 P.
  const int nb = b.k2 - b.k1 + 1;
  const double energy = SumOfSquares(
      {reinterpret_cast<const double*>(spectrum_.get() + b.k1), static_cast<size_t>(2 * nb)});
  const double rms = std::sqrt(energy / nb);
  std::vector<double> power(b.alpha_bins + 1, 0.0);
  if (!(rms > 0.0)) return power;  // an empty band: SE is 0
  const double inv_rms = 1.0 / rms;
  std::complex<float>* in = p.bins.get();
  for (int j = 0; j < nb; ++j) {
    const int k = b.k1 + j;
    const bool edge = (k == 0) || (2 * k == n_);
    const std::complex<double> v = spectrum_[k] * (edge ? 0.5 * inv_rms : inv_rms);
    in[j] = std::complex<float>(static_cast<float>(v.real()), static_cast<float>(v.imag()));
  }
  std::fill(in + nb, in + m, std::complex<float>(0.0f));
  p.inverse.Execute(in, p.envelope.get());

  // SE = |c|^2, packed as z_t = se_2t + i se_2t+1.
  const float* c = reinterpret_cast<const float*>(p.envelope.get());
  float* z = reinterpret_cast<float*>(p.packed.get());
  for (int t = 0; t < m; ++t) z[t] = c[2 * t] * c[2 * t] + c[2 * t + 1] * c[2 * t + 1];
  const double gain2 = rms * 2.0 / n_ * (rms * 2.0 / n_);
  PackedSesPower(&p, nullptr, m, b.alpha_bins, gain2, power.data());
  return power;
}

// The second half of the SES: the m samples of SE (any scale; gain2 makes it the true one) are
// in se, or already in p->packed when se is null; packed as z_t = se_2t + i se_2t+1 with the mean
// removed (computed in double), transformed, and P(k) = |FFT(SE - mean)_k|^2 / m^2 written for
// k = 1..alpha_bins to power[k], power[0] = 0.
// Multi-versioned (core/multiversion.h): the split of the half-size transform into the real one
// is a loop over every SES bin of every band the diagnosis searches.
SPALLKIT_MULTIVERSION
void EnvelopeAnalyzer::PackedSesPower(
    PlansF* pp, const float* se, int m, int alpha_bins, double gain2, double* power) {
  PlansF& p = *pp;
  float* z = reinterpret_cast<float*>(p.packed.get());
  const float* source = se ? se : z;
  const float mean = static_cast<float>(Sum(source, m) / m);
  for (int t = 0; t < m; ++t) z[t] = source[t] - mean;
  p.half.Execute(p.packed.get(), p.packed_spectrum.get());

  // X_k = E_k + w^k O_k with E_k = (Z_k + conj Z_{-k}) / 2, O_k = -i (Z_k - conj Z_{-k}) / 2
  // (indices mod m/2), w = e^{-2 pi i / m}: the real transform's bins, only up to alpha.
  const int h = m / 2;
  if (static_cast<int>(p.twiddle.size()) < alpha_bins + 1) {
    p.twiddle.resize(alpha_bins + 1);
    // Products of a coarse and a fine table (error ~1e-15), not one sincos per bin.
    const int fine = 64;
    std::complex<double> fine_w[fine];
    for (int i = 0; i < fine; ++i) fine_w[i] = std::polar(1.0, -2.0 * std::numbers::pi * i / m);
    for (int k = 0; k <= alpha_bins; k += fine) {
      const std::complex<double> coarse = std::polar(1.0, -2.0 * std::numbers::pi * k / m);
      for (int i = 0; i < fine && k + i <= alpha_bins; ++i) p.twiddle[k + i] = coarse * fine_w[i];
    }
  }
  const std::complex<float>* zs = p.packed_spectrum.get();
  const double scale = gain2 * gain2 / (double(m) * double(m));
  // 1 <= k <= alpha_bins <= h; Z's indices are taken mod h (k = h, the real transform's Nyquist
  // bin, only arises from SesPowerFromSquaredEnvelope). The complex arithmetic is written out
  // (std::complex's operator* checks for NaN and does not vectorise).
  const float* zf = reinterpret_cast<const float*>(zs);
  const double* tw = reinterpret_cast<const double*>(p.twiddle.data());
  auto bin = [&](int k, int kk, int hk) {
    const double zr = zf[2 * kk], zi = zf[2 * kk + 1];
    const double cr = zf[2 * hk], ci = -zf[2 * hk + 1];  // conj Z_{h-k}
    const double er = 0.5 * (zr + cr), ei = 0.5 * (zi + ci);
    const double o_r = 0.5 * (zi - ci), o_i = -0.5 * (zr - cr);  // -i (Z_k - conj Z_{h-k}) / 2
    const double wr = tw[2 * k], wi = tw[2 * k + 1];
    const double xr = er + wr * o_r - wi * o_i, xi = ei + wr * o_i + wi * o_r;
    power[k] = (xr * xr + xi * xi) * scale;
  };
  // k < h in one loop without index cases, k = h on its own.
  const int below_h = std::min(alpha_bins, h - 1);
  for (int k = 1; k <= below_h; ++k) bin(k, k, h - k);
  if (alpha_bins == h) bin(h, 0, 0);
  power[0] = 0.0;  // mean removed
}

std::vector<double> EnvelopeAnalyzer::SesPowerFromSquaredEnvelope(std::span<const float> se,
                                                                  double gain2,
                                                                  double max_alpha_hz,
                                                                  SesWorkspace* workspace) const {
  const int m = static_cast<int>(se.size());
  const double df = fs_hz_ / n_;
  const int alpha_bins =
      max_alpha_hz > 0
          ? static_cast<int>(std::floor(std::min(max_alpha_hz, 0.5 * fs_hz_) / df + 1e-9))
          : 0;
  if (!(max_alpha_hz > 0) || m % 2 != 0 || m < 2 * alpha_bins || m < 2) {
    std::ostringstream os;
    os << "envelope SES power from a squared envelope of " << m << " samples up to " << max_alpha_hz
       << " Hz: expected max_alpha > 0 and an even length of at least 2 x " << alpha_bins
       << " alpha bins";
    throw InputError(os.str());
  }
  auto& slot = workspace->plans_[m];
  if (!slot) slot = std::make_unique<PlansF>(m);
  PlansF& p = *slot;
  // The real samples go into the complex buffer pairwise (std::complex<float> is two floats) as
  // the mean is removed.
  std::vector<double> power(alpha_bins + 1, 0.0);
  PackedSesPower(&p, se.data(), m, alpha_bins, gain2, power.data());
  return power;
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
