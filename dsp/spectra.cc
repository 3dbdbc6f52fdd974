#include "dsp/spectra.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <sstream>

#include "core/error.h"
#include "dsp/fft.h"

namespace spallkit::dsp {
namespace {

void CheckInput(std::span<const double> x, double fs_hz, int segment, const char* what) {
  if (!(fs_hz > 0) || !std::isfinite(fs_hz)) {
    std::ostringstream os;
    os << what << ": sample rate must be > 0 Hz, got " << fs_hz;
    throw InputError(os.str());
  }
  if (x.size() < static_cast<size_t>(segment)) {
    std::ostringstream os;
    os << what << ": record has " << x.size() << " samples, fewer than one window of " << segment;
    throw InputError(os.str());
  }
  if (x.size() > static_cast<size_t>(1) << 30) {
    std::ostringstream os;
    os << what << ": record longer than 2^30 samples";
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

// Periodic Hann window (scipy.signal.get_window('hann', n)), the one for spectral analysis.
std::vector<double> PeriodicHann(int n) {
  std::vector<double> w(n);
  for (int i = 0; i < n; ++i) w[i] = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * i / n);
  return w;
}

// Windowed, mean-removed frame -> one-sided density |X|^2 / (fs sum w^2), inner bins doubled.
class FramePsd {
 public:
  FramePsd(int n, double fs_hz)
      : n_(n), fft_(n), window_(PeriodicHann(n)), frame_(n), spec_(n / 2 + 1) {
    double sw2 = 0;
    for (double w : window_) sw2 += w * w;
    scale_ = 1.0 / (fs_hz * sw2);
  }
  int bins() const { return n_ / 2 + 1; }
  // Adds (accumulate) or writes the frame's PSD into out[0..bins).
  void Run(const double* x, double* out, bool accumulate) {
    double mean = 0;
    for (int i = 0; i < n_; ++i) mean += x[i];
    mean /= n_;
    for (int i = 0; i < n_; ++i) frame_[i] = (x[i] - mean) * window_[i];
    fft_.Forward(frame_.data(), spec_.data());
    const int b = bins();
    for (int k = 0; k < b; ++k) {
      const bool single = (k == 0) || (2 * k == n_);
      const double p = std::norm(spec_[k]) * scale_ * (single ? 1.0 : 2.0);
      out[k] = accumulate ? out[k] + p : p;
    }
  }

 private:
  int n_;
  RealFft fft_;
  std::vector<double> window_, frame_;
  std::vector<std::complex<double>> spec_;
  double scale_ = 0;
};

}  // namespace

Spectrum WelchPsd(std::span<const double> x, double fs_hz, const WelchOptions& options) {
  if (options.segment < 8) {
    std::ostringstream os;
    os << "Welch segment must be >= 8 samples, got " << options.segment;
    throw InputError(os.str());
  }
  if (!(options.overlap >= 0 && options.overlap < 1)) {
    std::ostringstream os;
    os << "Welch overlap must be in [0, 1), got " << options.overlap;
    throw InputError(os.str());
  }
  CheckInput(x, fs_hz, options.segment, "Welch PSD");
  const int seg = options.segment;
  const int noverlap = std::min(seg - 1, static_cast<int>(std::lround(options.overlap * seg)));
  const int step = seg - noverlap;
  const int count = 1 + static_cast<int>((x.size() - seg) / step);

  FramePsd frame(seg, fs_hz);
  Spectrum out;
  out.psd.assign(frame.bins(), 0.0);
  for (int s = 0; s < count; ++s) {
    frame.Run(x.data() + static_cast<size_t>(s) * step, out.psd.data(), true);
  }
  for (double& p : out.psd) p /= count;
  out.resolution_hz = fs_hz / seg;
  out.freq_hz.resize(frame.bins());
  for (int k = 0; k < frame.bins(); ++k) out.freq_hz[k] = k * out.resolution_hz;
  out.segments = count;
  return out;
}

Spectrogram Stft(std::span<const double> x, double fs_hz, const StftOptions& options) {
  if (options.window < 8 || options.hop < 1) {
    std::ostringstream os;
    os << "STFT window must be >= 8 and hop >= 1, got window " << options.window << ", hop "
       << options.hop;
    throw InputError(os.str());
  }
  CheckInput(x, fs_hz, options.window, "STFT");
  const int win = options.window;
  const int hop = options.hop;
  Spectrogram out;
  out.frames = 1 + static_cast<int>((x.size() - win) / hop);
  FramePsd frame(win, fs_hz);
  out.bins = frame.bins();
  out.freq_resolution_hz = fs_hz / win;
  out.time_resolution_s = hop / fs_hz;
  out.freq_hz.resize(out.bins);
  for (int k = 0; k < out.bins; ++k) out.freq_hz[k] = k * out.freq_resolution_hz;
  out.time_s.resize(out.frames);
  out.power_db.resize(static_cast<size_t>(out.frames) * out.bins);
  for (int f = 0; f < out.frames; ++f) {
    const size_t start = static_cast<size_t>(f) * hop;
    out.time_s[f] = (start + 0.5 * win) / fs_hz;
    double* row = out.power_db.data() + static_cast<size_t>(f) * out.bins;
    frame.Run(x.data() + start, row, false);
    for (int k = 0; k < out.bins; ++k) row[k] = 10.0 * std::log10(std::max(row[k], 1e-30));
  }
  return out;
}

}  // namespace spallkit::dsp
