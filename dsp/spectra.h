// Power spectra and spectrograms with a Hann window, both on one reused FFTW plan.
#pragma once

#include <span>
#include <vector>

namespace spallkit::dsp {

// One-sided power spectral density, units^2/Hz: integrating psd over [0, fs/2] (sum * resolution)
// gives the variance of the signal (Parseval), and a sine of amplitude A gives a peak whose
// integral is A^2/2.
struct Spectrum {
  std::vector<double> freq_hz, psd;
  double resolution_hz = 0;
  int segments = 0;  // number of averaged segments
};

// Welch's method with a periodic Hann window, each segment's mean removed ("constant" detrend),
// density scaling |X|^2 / (fs * sum w^2), non-DC non-Nyquist bins doubled, plain average. Matches
// scipy.signal.welch(x, fs, nperseg=segment, noverlap=round(overlap*segment)).
struct WelchOptions {
  int segment = 4096;    // samples per segment, >= 8
  double overlap = 0.5;  // fraction of a segment shared by consecutive segments, in [0, 1)
};
// Throws InputError if fs <= 0, the options are out of range, a sample is not finite or x is
// shorter than one segment.
Spectrum WelchPsd(std::span<const double> x, double fs_hz, const WelchOptions& options = {});

// Short-time Fourier transform power in dB (10 log10 of the one-sided PSD of each frame, same
// scaling as WelchPsd, floored at -300 dB), periodic Hann window, frame mean removed.
// Frame f covers samples [f*hop, f*hop + window); time_s is its centre.
struct Spectrogram {
  std::vector<double> time_s, freq_hz;
  std::vector<double> power_db;  // row-major [time][freq], frames x bins
  int frames = 0, bins = 0;
  double freq_resolution_hz = 0;  // fs / window
  double time_resolution_s = 0;   // hop / fs (frame spacing)
  double at(int frame, int bin) const { return power_db[static_cast<size_t>(frame) * bins + bin]; }
};
struct StftOptions {
  int window = 1024;  // >= 8
  int hop = 256;      // >= 1
};
Spectrogram Stft(std::span<const double> x, double fs_hz, const StftOptions& options = {});

}  // namespace spallkit::dsp
