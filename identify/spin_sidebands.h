// The f_c sideband pattern of the roller comb: complex squared-envelope spectrum lines at
// j f_s + m f_c (f_s = f_b / 2 the roller spin rate, j = 1..J spin harmonics, m = -M..M; or on
// the even ones only, j f_b + m f_c: IdentifyOptions::sideband_spin_step), the
// count's second feature, independent of the cage-synchronous average (which holds only the
// j = 0 lines: the impacts at f_b are not synchronous with the cage and average out of it).
//
// Why it counts rollers: roller k (cage slot s_k, spall at spin phase phi_k, strength a_k)
// contributes to line (j, m) the phasor
//     M_m e^{-i m theta_0} a_k p_j e^{-i j phi_k} e^{i m 2 pi s_k / Z}
// (M_m the Fourier coefficients of the load-zone hump, p_j those of one spin turn's impacts).
// With one roller the pattern over m is the hump's own, M_m e^{-i m theta_0}, times one complex
// number per harmonic. Several rollers at different slots and spin phases interfere: the pattern
// over m is a sum of K "steering vectors" e^{i m 2 pi s_k / Z} with free complex weights, which
// no single hump reproduces (upper and lower sidebands become unequal). This separates adjacent
// rollers whose humps overlap in the cage average.
//
// Each line is the record's DFT at the exact frequency (mean removed, divided by the sample
// count), and its noise power is the squared-envelope spectrum's local floor: the median of |X|^2
// over +/- window_bins around it, leaving out bins within 2 bins of any comb line, / ln 2 (the
// median of an exponential variable is ln 2 times its mean).
#pragma once

#include <complex>
#include <span>
#include <vector>

namespace spallkit::identify {

struct SpinSidebands {
  double spin_hz = 0.0;  // the base rate of the harmonics j (f_s, or f_b with spin_step 2)
  double cage_hz = 0.0;
  int harmonics = 0;                        // J
  int orders = 0;                           // M
  std::vector<std::complex<double>> value;  // (j - 1) * (2M + 1) + (m + M)
  std::vector<double> noise_power;          // E|noise|^2 per line

  int Index(int j, int m) const { return (j - 1) * (2 * orders + 1) + (m + orders); }
  double FrequencyHz(int j, int m) const { return j * spin_hz + m * cage_hz; }
};

// The highest line MeasureSpinSidebands measures (j = harmonics, m = orders), Hz: a squared
// envelope must hold it alias-free for all of them to be measured.
inline double SidebandsHighestLineHz(
    double spin_hz, double cage_hz, int harmonics, int orders, int spin_step = 1) {
  return harmonics * spin_step * spin_hz + orders * cage_hz;
}

// Lines of se (sampled at rate_hz, first sample at t = 0) at j (spin_step spin_hz) + m cage_hz:
// spin_step 2 takes the harmonics of f_b = 2 f_s (the result's spin_hz is then f_b). Every spin
// harmonic's comb is kept out of the floors. Lines above the Nyquist rate of se are left out
// (harmonics reduced so that every line fits).
SpinSidebands MeasureSpinSidebands(std::span<const double> se,
                                   double rate_hz,
                                   double spin_hz,
                                   double cage_hz,
                                   int harmonics = 4,
                                   int orders = 4,
                                   int spin_step = 1,
                                   int window_bins = 60);

}  // namespace spallkit::identify
