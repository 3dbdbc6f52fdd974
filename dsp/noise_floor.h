// The robust local noise floor of a power spectrum (an SES), against which every line is tested.
//
// For Gaussian noise in the demodulation band the SES power P(a) at a cyclic frequency a is
// ~ exponential around its local mean mu(a) (chi^2 with 2 dof). mu(a) is estimated robustly by a
// running median of the neighbouring bins divided by ln 2 (median of an exponential = ln 2 x mean);
// z = P / mu. Because mu is itself estimated from W bins, the bin tail is the Lomax law
// P(z > t) = (1 + t/n)^-n with n = W ln^2 2 (the median's efficiency), not e^-t.
#pragma once

#include <span>
#include <vector>

namespace spallkit::dsp {

// A power spectrum normalised by its robust local floor.
struct NormalizedSpectrum {
  std::vector<double> power;  // input power, bin i at i * resolution_hz
  std::vector<double> floor;  // local mean estimate mu
  std::vector<double> z;      // power / floor
  double resolution_hz = 0.0;
  double effective_samples = 0.0;  // n of the Lomax tail
  double envelope_mean = 0.0;      // mean of the squared envelope (level units), 0 = unknown

  // Null probability that one bin exceeds z.
  double BinTail(double z_value) const;
  // Null p-value of the larger of two adjacent bins.
  double PairPValue(double z_value) const;
};

// Running median / ln 2 over window_bins bins (the window is shifted, not clipped, at the
// spectrum edges; bin 0 is ignored). Computed every few bins and interpolated linearly. Throws
// InputError when the spectrum has no more than window_bins bins or the resolution is <= 0.
// With a shape (as many values as bins, > 0): the spectrum's expected form, so the median runs
// on the flattened power / shape, z = (power / shape) / that floor, and floor is multiplied back
// by the shape.
NormalizedSpectrum NormalizeSpectrumWindow(std::span<const double> power,
                                           double resolution_hz,
                                           int window_bins,
                                           std::span<const double> shape = {});

}  // namespace spallkit::dsp
