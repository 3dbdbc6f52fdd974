// Spectral lines at exact (non-bin) frequencies of a sampled signal, and the rate at which a
// family of such lines is strongest: what the identification uses to refine the diagnosis's
// measured f_c and f_b to a fraction of a bin before folding the record at them.
#pragma once

#include <complex>
#include <span>

namespace spallkit::identify {

// The rate within +/- half_range_hz of guess_hz that maximises sum_{j=1..orders} |DFT(se)(j f)|^2
// / j over a grid of `steps` points, refined by a parabola through the best three. Used for the
// cage rate (humps) and the spin rate (impacts) alike.
double RefineRate(std::span<const double> se,
                  double rate_hz,
                  double guess_hz,
                  double half_range_hz,
                  int orders = 3,
                  int steps = 41);

// The DFT of se at one frequency, sum_t (se_t - mean) e^{-2 pi i f t} / n.
std::complex<double> DftAt(std::span<const double> se, double mean, double rate_hz, double f_hz);

}  // namespace spallkit::identify
