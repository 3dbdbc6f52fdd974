// Squared-envelope spectrum (SES) by the one-sided band method ("Hilbert process", Randall 2015,
// Modern envelope analysis for bearing diagnostics).
//
// For a demodulation band [f1, f2] the steps are:
//   1. X = FFT of the whole record (mean removed), done once per record;
//   2. keep the one-sided bins k1..k2 of [f1, f2], doubled (the analytic signal's spectrum): an
//      ideal band-pass that can sit right next to strong discrete lines;
//   3. shift bin k1 to DC and inverse-transform at a small size M >= (k2-k1+1) + alpha bins
//      (FftFastSize): this is the complex envelope decimated to fs' = M * fs / N with no
//      aliasing of |c|^2 below max_alpha (|c|^2 spans +-(k2-k1) bins, so its images start at
//      M-(k2-k1) > alpha bins). The shift changes only the phase of c, not |c|;
//   4. SE = |c|^2, mean removed, real FFT of size M; SES(alpha) = |FFT(SE - mean)| / M, which
//      equals the full-rate |FFT(SE - mean)| / N because the decimated SE holds exactly the same
//      samples' spectral content below max_alpha.
// Level convention: a squared-envelope component a*cos(2 pi alpha t) appears with level a/2 (the
// |FFT|/N convention of Randall's papers; it is not doubled). The spectral resolution is fs/N, as
// for a full-rate SES of the same record.
//
// Squared (default) because SES(alpha) ~ integral over the band of the spectral correlation
// S_x(alpha, f) (Randall & Antoni 2011); the amplitude envelope |c| (squared = false, what MATLAB's
// envspectrum returns) adds spurious harmonics and, not being band-limited, aliases slightly at the
// decimated rate.
#pragma once

#include <complex>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "dsp/band.h"
#include "dsp/fft.h"

namespace spallkit::dsp {

struct EnvelopeSpectrum {       // one-sided, alpha = 0 .. max_alpha
  std::vector<double> freq_hz;  // cyclic frequency alpha, k * resolution_hz
  std::vector<double> level;    // |FFT(SE - mean)| / N (or of the amplitude envelope); level[0] = 0
  double resolution_hz = 0;     // bin spacing, fs / N
  Band band;                    // demodulation band used (as requested)
  bool squared = true;
  double envelope_rate_hz = 0;  // sample rate of the decimated envelope that was transformed
};

struct EnvelopeOptions {
  double max_alpha_hz = 0;  // highest cyclic frequency returned; 0: the band width
  bool squared = true;      // false: amplitude envelope |c| instead of |c|^2
};

// Analyses one record: the forward FFT is done once in the constructor, then any number of bands
// cost only the small transforms of their decimated envelopes. Plans for each decimated size are
// cached in the object and reused across calls. Not thread-safe (one analyser per thread), except
// the const SesPowerFast overload, which takes the thread's own SesWorkspace.
class EnvelopeAnalyzer {
 private:
  struct PlansF;

 public:
  // Buffers and cached plans of SesPowerFast (one set per decimated size). Several threads may
  // call SesPowerFast(..., workspace) on one analyser at once, each with its own workspace:
  // the record's spectrum is only read, and FFTW plans are made under a mutex (dsp/fft.h).
  class SesWorkspace {
   public:
    SesWorkspace();
    ~SesWorkspace();
    SesWorkspace(SesWorkspace&&) noexcept;
    SesWorkspace& operator=(SesWorkspace&&) noexcept;

   private:
    friend class EnvelopeAnalyzer;
    std::map<int, std::unique_ptr<PlansF>> plans_;
  };

  // Minimum record length accepted.
  static constexpr int kMinSamples = 64;

  // Throws InputError if x has fewer than kMinSamples samples, a non-finite sample, or fs <= 0.
  EnvelopeAnalyzer(std::span<const double> x, double fs_hz);
  ~EnvelopeAnalyzer();
  EnvelopeAnalyzer(EnvelopeAnalyzer&&) noexcept;
  EnvelopeAnalyzer& operator=(EnvelopeAnalyzer&&) noexcept;

  // Analyser of the cepstrum-pre-whitened record (dsp/prewhiten.h): identical, to rounding, to
  // EnvelopeAnalyzer(CepstrumPrewhiten(x), fs_hz), with one FFT of the record instead of three.
  static EnvelopeAnalyzer Prewhitened(std::span<const double> x, double fs_hz);
  // Pre-whitens this analyser's record in place: afterwards it is Prewhitened(x, fs_hz) of the
  // record it was made from, without a transform of the record.
  void Whiten();

  double sample_rate_hz() const { return fs_hz_; }
  int size() const { return n_; }
  double resolution_hz() const { return fs_hz_ / n_; }
  // One-sided FFT of x with the mean removed (bin 0 is zero), n/2+1 bins, unnormalised.
  std::span<const std::complex<double>> spectrum() const {
    return {spectrum_.get(), static_cast<size_t>(n_ / 2 + 1)};
  }

  // Envelope spectrum for a band. The band must satisfy 0 <= low < high <= fs/2 and contain at
  // least one FFT bin; max_alpha_hz must be >= 0. Otherwise throws InputError.
  EnvelopeSpectrum Compute(const Band& band, const EnvelopeOptions& options = {});

  // The squared envelope time signal |c|^2 for a band (mean kept), decimated alias-free up to
  // max_alpha_hz (0: the band width); its sample rate is returned in *rate_hz (may be null). It
  // spans the whole record; scaled so that a band holding a sine of amplitude A gives SE = A^2.
  std::vector<double> SquaredEnvelope(const Band& band, double max_alpha_hz, double* rate_hz);

  // SES power P(alpha) = |FFT(SE - mean)|^2 / m^2, i.e. Compute(band, {max_alpha_hz}).level
  // squared, for alpha = k * resolution_hz, k = 0 .. floor(min(max_alpha_hz, fs/2) / df)
  // (max_alpha_hz must be > 0), with the two transforms in single precision (fftwf; the band's
  // bins are scaled to unit RMS first, so no record is too small or large for floats) and the
  // second one a half-size complex transform of which only the bins up to max_alpha are formed.
  // Faster than Compute() (bench/dsp_benchmark); each bin within ~3e-6 relative of the
  // double-precision value (of the noise floor's level, for bins below it): what a detection
  // statistic needs (the diagnosis searches many bands this way). *envelope_size (may be null)
  // receives the decimated envelope's length m.
  std::vector<double> SesPowerFast(const Band& band, double max_alpha_hz, int* envelope_size);
  // Same, with the caller's workspace (bit-identical results): thread-safe as described above.
  std::vector<double> SesPowerFast(const Band& band,
                                   double max_alpha_hz,
                                   int* envelope_size,
                                   SesWorkspace* workspace) const;

  // SES power, as SesPowerFast returns it, from a squared envelope already at hand: se holds m
  // samples of |c|^2 over the whole record (m even, sample s at time s * N / (m fs), e.g. a
  // kurtogram node's, Kurtogram::squared_envelopes) in any scale, gain2 the factor that makes it
  // the true squared envelope (EnvelopeAnalyzer's convention). The band's bins are whatever c
  // holds; the result is alias-free up to max_alpha_hz when m exceeds the band's bins plus the
  // alpha bins (m >= 2 B does it for alpha up to the band width). Costs one half-size complex
  // transform (no inverse transform of the band). Throws InputError if max_alpha_hz <= 0, m is
  // odd or m < 2 alpha bins. Thread-safe with the caller's workspace.
  std::vector<double> SesPowerFromSquaredEnvelope(std::span<const float> se,
                                                  double gain2,
                                                  double max_alpha_hz,
                                                  SesWorkspace* workspace) const;

  // The complex envelope c (analytic signal of the band-passed record, shifted down by the band's
  // first bin frequency) at the decimated rate, written to *out (resized); returns the rate.
  double ComplexEnvelope(const Band& band,
                         double max_alpha_hz,
                         std::vector<std::complex<double>>* out);

 private:
  struct Plans;
  struct BandBins {
    int k1, k2, alpha_bins, m;
  };
  BandBins Resolve(const Band& band, double max_alpha_hz) const;
  Plans& PlansFor(int m);
  void FillEnvelope(const BandBins& bins);  // writes c into work_ of plans for bins.m
  // The SES from SE in se, or packed in plans->packed when se is null (SesPowerFast,
  // SesPowerFromSquaredEnvelope).
  static void PackedSesPower(
      PlansF* plans, const float* se, int m, int alpha_bins, double gain2, double* power);

  int n_ = 0;
  double fs_hz_ = 0;
  // n/2 + 1 bins, FFTW-aligned so the record's transform writes it directly (no zero fill, no
  // scratch copy: a 10 s record at 48 kHz has 3.8 MB of them).
  FftwArray<std::complex<double>> spectrum_;
  std::map<int, std::unique_ptr<Plans>> plans_;
  SesWorkspace ses_workspace_;  // SesPowerFast's, for the non-const overload
};

// One-shot convenience: EnvelopeAnalyzer(x, fs).Compute(band, options).
EnvelopeSpectrum SquaredEnvelopeSpectrum(std::span<const double> x,
                                         double fs_hz,
                                         const Band& band,
                                         const EnvelopeOptions& options = {});

}  // namespace spallkit::dsp
