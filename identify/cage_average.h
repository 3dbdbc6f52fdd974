// Cage-synchronous average of a squared envelope: the signal folded over the cage's revolution.
//
// A defective roller strikes only while it crosses the load zone, once per cage revolution at its
// own cage angle, so the squared envelope averaged synchronously with the cage (cage phase
// Phi(t) = 2 pi f_c t, folded modulo 2 pi into equal bins) shows one load-zone hump per
// defective roller. The impacts at f_b are not synchronous with the cage (f_b / f_c is not an
// integer), so over the revolutions they fill the hump instead of forming peaks.
//
// Each bin's standard error comes from the scatter between whole revolutions (so it holds the
// envelope's correlation within a revolution and the impacts' own variability), pooled over
// neighbouring bins to steady the estimate of a few revolutions.
#pragma once

#include <span>
#include <vector>

namespace spallkit::identify {

struct CageAverage {
  double cage_hz = 0.0;
  double revolutions = 0.0;  // record length in cage revolutions
  int whole_revolutions = 0;
  // Bin i covers cage phase [i, i + 1) * 2 pi / bins; phase 0 at the record's first sample.
  std::vector<double> mean;   // average squared envelope
  std::vector<double> sigma;  // standard error of the mean
  int bins() const { return static_cast<int>(mean.size()); }
  double BinCenterRad(int i) const;
};

// Folds se (sampled at rate_hz, first sample at t = 0) at cage_hz into `bins` bins. sigma uses
// the whole revolutions (>= 2 needed, else sigma is from the within-bin scatter assuming
// independent samples), pooled over +/- pool_bins neighbours. Bins with no sample are not allowed:
// bins must be <= samples per revolution.
CageAverage AverageOverCage(
    std::span<const double> se, double rate_hz, double cage_hz, int bins, int pool_bins = 2);

}  // namespace spallkit::identify
