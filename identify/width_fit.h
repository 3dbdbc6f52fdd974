// Spall width from the time between a spall passage's two events: entry (the roller's edge leaves
// the race: the contact unloads, a weaker ring-down) and exit (the roller lands on the trailing
// edge: the main impulse), separated by dt = chord angle / spin rate, i.e. w = d sin(pi f_s dt)
// for a chord w on a roller of diameter d spinning at f_s relative to the cage (identify/identify.h
// turns dt into a width with the calibration of docs/IDENTIFY.md).
//
// Feature: the autocorrelation of the squared envelope (floor removed) inside the load zone,
//     R(tau) = < (SE(t) - b) (SE(t + tau) - b) >_{t in load zone},
// i.e. the average over all passages of each passage's envelope times itself delayed, which needs
// no alignment of the passages: the entry-exit pair puts a peak at tau = dt whatever the
// passage-to-passage slip, noise only adds near tau = 0 (its correlation time is 1 / band width),
// and impacts of the other race fall a half spin turn (1 / f_b) away. Another defective roller's
// impacts correlate at the lag of the two rollers' spin phases: the fit does not know them, and
// the identification refuses a delay that lands on one (IdentifyOptions::cross_lag_half_width_s).
// Passages are not aligned on their exit peaks: aligning on noisy peaks sharpens the exit
// and shifts the entry (on 10 dB synthetic records dt comes out 13 % long, with bootstrap
// intervals that miss the truth).
//
// Model for tau in [0, max_delay + tail]:
//     R(tau) = c + P_0 S(tau; sigma_0, tau_d) + P_1 S(tau - dt; sigma_1, tau_d1) + P_n N(tau)
// S the symmetric exponentially modified Gaussian, [E(tau) + E(-tau)] / 2 (E the EMG with rise
// sigma and ring-down tau_d: an event's squared envelope correlated with itself), sigma_1 >=
// sigma_0 (the delay jitters between passages), tau_d1 the pair peak's own ring-down (tau_d with
// WidthFitOptions::shared_ring_down); N a Gaussian of the noise's correlation time
// (about 1 / band width: the noise correlates only with itself near tau = 0). (c, P_0, P_1, P_n)
// are linear; dt is searched on a grid
// from min_delay_s to max_delay_s with a few shapes, then every parameter is refined with Ceres.
//
// Standard errors per lag from the scatter between blocks (one per cage revolution), pooled over
// +/- 2 lags. Interval: percentiles of dt over a bootstrap of the blocks (each resample averaged
// and refitted), widened to at least +/- t(0.95, n - 1) bootstrap standard deviations (with n
// blocks: a bootstrap of 8-16 blocks is too narrow otherwise). ceres::Covariance's standard error
// (independent lags) is reported beside it.
#pragma once

#include <algorithm>
#include <span>
#include <string>
#include <vector>

namespace spallkit::identify {

struct WidthFitOptions {
  double min_delay_s = 0.0;  // search range of dt; 0: two envelope samples
  double max_delay_s = 2.5e-3;
  double tail_s = 1.5e-3;  // lags fitted beyond max_delay_s
  int delay_grid = 80;
  int bootstrap = 200;  // resamples for the delay's interval (< 10: none; AddDelayInterval)
  int min_blocks = 3;   // blocks (cage revolutions) with load-zone samples
  // Correlation time of the band's noise (about 1 / band width; the Gaussian peak P_n at tau = 0
  // takes it); 0: one sample (white).
  double noise_correlation_s = 0.0;
  // The two peaks' ring-downs: each its own, the pair peak's at most the zero-lag peak's (the
  // default: each side of the pair peak decays with one event's ring-down, the zero-lag peak with
  // the slowest event's; a shared tau_d misfits a pair peak sharper than the zero-lag peak, and
  // the best fit over every delay can then take a faint far lag instead, docs/IDENTIFY.md,
  // "Width"), or one tau_d for both (true: for comparisons and the synthetic signal model).
  bool shared_ring_down = false;
  unsigned seed = 1;

  bool IsValid(std::string* error) const;
};

// The load-zone autocorrelation of a squared envelope, with per-lag standard errors.
struct EnvelopeCorrelation {
  double rate_hz = 0.0;
  double floor = 0.0;                       // b: median of the squared envelope in the zone
  std::vector<double> mean, sigma;          // per lag tau_i = i / rate_hz
  std::vector<std::vector<double>> blocks;  // per block: sum of products per lag (and count)
  std::vector<double> block_counts;
  double TauSeconds(int i) const { return i / rate_hz; }
};

// R(tau) for lags 0..lags-1 over the samples with in_zone set (all when empty), in blocks of
// block_samples consecutive samples.
EnvelopeCorrelation CorrelateInZone(std::span<const double> se,
                                    double rate_hz,
                                    const std::vector<char>& in_zone,
                                    int lags,
                                    int block_samples);

struct EntryExitFit {
  double offset = 0.0;               // c
  double zero_lag_power = 0.0;       // P_0
  double delay_power = 0.0;          // P_1
  double noise_power = 0.0;          // P_n: the noise's own peak around tau = 0
  double noise_correlation_s = 0.0;  // its width
  double delay_s = 0.0;              // dt
  double rise_s = 0.0;               // sigma_0
  double delay_rise_s = 0.0;         // sigma_1
  double decay_s = 0.0;              // tau_d
  double delay_decay_s = 0.0;        // tau_d1, the second event's ring-down (0: tau_d's)
  double chi2 = 0.0;
  std::vector<double> model;

  // The second event's correlation over the zero-lag power (noise included): at most 1/2 for two
  // events, about 1/2 for two of like strength, while the noise term is narrower than an event.
  // noise_power is a height, the others areas: where the noise term is as wide as an event the
  // fit can move zero-lag power into it and the ratio of a true pair passes 1.
  double PairPowerRatio() const {
    return delay_power / std::max(1e-300, zero_lag_power + noise_power);
  }
  // The pair peak's ring-down: tau_d1, or tau_d where it has none of its own.
  double PairDecayS() const { return delay_decay_s > 0 ? delay_decay_s : decay_s; }
};

struct WidthFit {
  bool usable = false;  // a fit was made
  std::string message;  // why not, when not
  int blocks = 0;
  EntryExitFit best;
  double delay_standard_error_s = 0.0;           // ceres::Covariance (independent lags)
  double delay_low_s = 0.0, delay_high_s = 0.0;  // 90 % bootstrap interval
  // Is there a second event at all: sqrt of the chi2 gain over the fit without it, in units of
  // the best fit's reduced chi2 and of the lags' correlation length (about 2 rise times).
  double delay_power_significance = 0.0;
  EnvelopeCorrelation correlation;
};

// The exponentially modified Gaussian E(tau) and its symmetric form S; exposed for tests.
double EventShape(double tau_s, double rise_s, double decay_s);
double SymmetricEventShape(double tau_s, double rise_s, double decay_s);

// Fits the model to the load-zone autocorrelation of se (blocks of block_samples), with the
// delay's bootstrap interval (AddDelayInterval).
WidthFit FitEntryExit(std::span<const double> se,
                      double rate_hz,
                      const std::vector<char>& in_zone,
                      int block_samples,
                      const WidthFitOptions& options);

// The 90 % bootstrap interval of a usable fit's delay (options.bootstrap resamples of its blocks,
// none below 10: the interval is then the estimate). FitEntryExit does it; a caller that fitted
// with bootstrap < 10 to judge the fit first can add it afterwards, with the same result.
void AddDelayInterval(const WidthFitOptions& options, WidthFit* fit);

}  // namespace spallkit::identify
