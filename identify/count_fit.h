// Number and cage positions of the defective rollers: K = 0..max_count load-zone humps fitted to
// the cage-synchronous average of the squared envelope (feature A, identify/cage_average.h) and
// the same slot configuration's interference pattern in the f_c sidebands of the roller comb
// (feature B, identify/spin_sidebands.h), compared by evidence.
//
// Feature A, bin i at cage phase phi_i:
//     y_i = b + sum_k a_k H(phi_i - theta_0 + 2 pi s_k / Z),   s_1 = 0 < s_2 < ... < s_K < Z
// s_k the cage slots of the defective rollers (roller s is 2 pi s / Z ahead of roller 0 in the
// direction of rotation, so its hump comes 2 pi s / Z earlier in cage phase), a_k >= 0 their
// strengths, b the floor, theta_0 the cage phase at which slot 0 crosses the load line.
// H(x) = q^p (1 + beta (1 - q)) [cos^2(x - sensor angle)] smoothed: q(x) the Harris-Jones relative
// load with half angle psi_l (identify/load_zone.h; fixed when the record's load is given, else
// fitted in 20-100 deg), p the exponent of the squared envelope's growth with load (fitted,
// 0.25..6), beta >= 0 (fitted,
// <= 20) the extra strength of impacts near the load zone's edges (spallkit's simulated spalls
// strike 2-3x harder at +/- 40 deg than on the load line: the roller falls further before the
// lighter load catches it), smoothed by a Gaussian of std sigma_s (cage-speed jitter and the bin
// width; fitted, 0.3 bin widths..max_smear_rad; 3-point Gauss-Hermite).
//
// Feature B, line (j, m) of SpinSidebands:
//     S_jm = p_j M_m e^{-i m (theta_0 + delta)} sum_k a_k e^{-i j phi_k} e^{i m 2 pi s_k / Z},
// M_m the Fourier coefficients of H (without the bin width); theta_0, the shape and the strengths
// a_k from feature A's fit of the same configuration; delta a common offset within +/- half a
// slot; phi_k the spall's phase on roller k at the lines' base rate (f_s, or f_b where they are
// the harmonics of f_b: IdentifyOptions::sideband_spin_step; phi_1 = 0, the others on a grid of
// 24, two coordinate sweeps); p_j one complex factor per harmonic (impact spectrum, outer/inner
// alternation, slip smear), by least squares.
// With CountFitOptions::sideband_pattern_per_parity (not the default) instead
//     S_jm = p_j G^(j mod 2)_m sum_k a_k e^{-i j phi_k} e^{i m 2 pi s_k / Z},
// G^0 and G^1 the cage-angle patterns of the even and the odd spin harmonics (complex per order,
// shared by the rollers, fitted from M_m e^{-i m theta_0} by alternating least squares with p_j
// and a_k): a roller strikes the outer race at spin phase phi_k and the inner race half a turn
// later, so its odd harmonics carry the difference of the two races' impacts and its even ones
// their sum, and the two reach the sensor with different weights over the cage angle.
//
// With CountFitOptions::sideband_second_pattern (not the default; not with the per-parity
// patterns) each roller carries a second pattern N_m, real and symmetric about its load-line
// crossing (like M_m), fitted and shared by the rollers and the harmonics:
//     S_jm = sum_k a_k e^{-i j phi_k} e^{i m (2 pi s_k / Z - theta_0 - delta)} (p_j M_m + q_j N_m),
// q_j complex per harmonic: a wide spall's lines hold two such patterns (docs/IDENTIFY.md, "Where
// the failures lie").
//
// Search. A configuration is the slot set up to rotation (a necklace containing slot 0): 1 for
// K = 1, 6 for K = 2 and 22 for K = 3 on 13 slots. Up to exhaustive_max_count every configuration
// is screened (feature A by weighted linear least squares in (b, a) with a fixed shape, on a grid
// of theta_0 of theta_grid_per_slot Z points; feature B linear as above), and the best `refine`
// of each K (by both features) are refitted in all of feature A's parameters with Ceres. The
// shape is that of the best K = 1 fit, then (second pass) that of the most probable K. Above
// exhaustive_max_count the search is greedy (the best configuration of K - 1 plus one slot).
// Configurations with a hump weaker than min_relative_amplitude of their strongest are not
// counted (such a "roller" is indistinguishable from a misfit of the shape).
//
// Evidence. Per configuration and feature the BIC approximation ln Z = -chi2 / 2 - k/2 ln n (k
// parameters, n data); per K the mean over all its configurations (each equally likely a
// priori; those not searched or not counted add nothing); P(K) with a uniform prior on K. When
// the best model's reduced chi2 of a feature exceeds 1 (the model misses something its standard
// errors do not cover), that feature's chi2 are all divided by it, so a poor fit cannot make a
// confident choice. The features are independent given the configuration (disjoint spectral
// lines), so the combined evidence is the sum of the two.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "identify/cage_average.h"
#include "identify/spin_sidebands.h"

namespace spallkit::identify {

struct CountFitOptions {
  int max_count = -1;  // largest K tried; -1: Z (every roller)
  int refine = 3;      // configurations per K refitted with Ceres (K <= exhaustive_max_count)
  int exhaustive_max_count = 3;
  int theta_grid_per_slot = 4;
  // 0.25: on the simulator's records, spalls also strike outside the load zone (humps of 10-20 %
  // of the load-zone one) and must not count as rollers (docs/IDENTIFY.md, "Calibration").
  double min_relative_amplitude = 0.25;
  double max_smear_rad = 0.15;  // upper bound of sigma_s (~8.6 deg)
  // Model tolerance: every bin's standard error is widened (in quadrature) by this fraction of the
  // average's range, every line's noise by this fraction of its harmonic's largest line. Details
  // below it (lumps of a few revolutions' impacts, a small cage-synchronous knock outside the load
  // zone) are not the humps' business and must not decide the count.
  double model_tolerance = 0.03;
  // The sensor's direction from the load line (rad), when known: the humps are then weighted by
  // cos^2(psi - this) (0: on the load line, a vertical accelerometer under a vertical load;
  // pi/2: a horizontal one). Unset: no projection (the fitted exponent and edge gain absorb a
  // sensor near the load line).
  std::optional<double> sensor_angle_rad;
  // Half angle of the load zone (rad): > 0 fixes it (from the record's load), 0 fits it.
  double load_zone_half_angle_rad = 0.0;
  bool use_sidebands = true;  // feature B (when sidebands are given)
  // Feature B with one cage-angle pattern per parity of the spin harmonic, fitted and shared by
  // the rollers, instead of feature A's hump for every harmonic (see "Feature B" above). Off by
  // default: measured, not adopted (docs/IDENTIFY.md, "Feature B's patterns per parity").
  bool sideband_pattern_per_parity = false;
  // Feature B with a second cage-angle pattern per roller (real, symmetric about the roller's
  // load-line crossing, fitted and shared by the rollers and harmonics; docs/IDENTIFY.md).
  bool sideband_second_pattern = false;
  // Temperatures of each feature's log evidence: P(K) is proportional to
  // exp(ln Z_A(K) / temperature_cage + ln Z_B(K) / temperature_sidebands). The BIC evidence
  // assumes the model is right up to independent noise; on simulated records it is not (the
  // hump shape and the sideband pattern miss details that grow with the number of lines), so the
  // temperatures are calibrated on simulated records of known count (docs/IDENTIFY.md,
  // "Calibration"): the values that maximise the mean log probability of the true count.
  double temperature_cage = 5.0;
  double temperature_sidebands = 28.0;
  // Combine the features per K (each feature's evidence averaged over the configurations of K,
  // then tempered), as the temperatures were chosen (scripts/choose_temperatures.py), instead of
  // per configuration (tempered, then averaged). Measured, not the default (docs/IDENTIFY.md).
  bool combine_per_count = false;
  // Feature B is evaluated only for configurations whose feature-A chi2 is within this of the
  // best (the others cannot matter; B is the costly part).
  double sideband_screen_chi2 = 60.0;
  int max_iterations = 100;

  bool IsValid(std::string* error) const;
};

// The range of the strength law's exponent p that the fits search.
constexpr double kHumpMinExponent = 0.25, kHumpMaxExponent = 6.0;

struct HumpShape {
  double exponent = 1.0;        // p
  double edge_gain = 0.0;       // beta
  double smear_rad = 0.05;      // sigma_s
  double half_angle_rad = 1.2;  // psi_l
  bool half_angle_fixed = false;
  double sensor_angle_rad = 0.0;  // fixed: CountFitOptions::sensor_angle_rad
  bool sensor_projection = false;

  // The strength law's highest value over its value on the load line, max over q of
  // q^p (1 + beta (1 - q)): 1 for a hump that peaks on the load line, larger where the edge gain
  // raises its flanks above its centre.
  double EdgeToCentre() const;
};

// One fitted configuration.
struct HumpFit {
  std::vector<int> slots;          // s_k, ascending, slots[0] = 0 (empty for K = 0)
  std::vector<double> amplitudes;  // a_k
  double floor = 0.0;              // b
  double theta0_rad = 0.0;
  HumpShape shape;
  double chi2 = 0.0;            // feature A
  double chi2_sidebands = 0.0;  // feature B (0 when not used)
  // Feature B's spall spin phases phi_k (phi_1 = 0): roller k strikes (phi_k - phi_1) / (2 pi f_s)
  // after roller 1, modulo half a spin turn.
  std::vector<double> spin_phase_rad;
  bool refined = false;       // Ceres-refined (else from the linear screen)
  std::vector<double> model;  // feature A's model per bin
};

struct CountFit {
  int slots = 0;  // Z
  int bins = 0;
  int sideband_lines = 0;             // complex lines of feature B (0: not used)
  double chi2_scale = 1.0;            // feature A's Birge factor (>= 1)
  double chi2_scale_sidebands = 1.0;  // feature B's
  // Per K = 0..max_count: log evidence and probability of each feature alone and combined (the
  // combined log evidence and all probabilities with the temperatures applied).
  std::vector<double> log_evidence_cage, log_evidence_sidebands, log_evidence;
  std::vector<double> probability_cage, probability_sidebands, probability;
  std::vector<HumpFit> best;                      // best configuration per K (combined evidence)
  std::vector<double> configuration_probability;  // of best[K] among the configurations of K
  int MostProbable() const;
};

// The necklaces of `count` slots out of `slots` that contain slot 0, each as its canonical
// rotation (the one spanning the smallest arc from 0, then lexicographically smallest).
std::vector<std::vector<int>> SlotConfigurations(int slots, int count);

// The same slot set rotated to its canonical form (see SlotConfigurations).
std::vector<int> CanonicalSlots(const std::vector<int>& slots, int z);

// Fits K = 0..max_count to the average and, when given, the sidebands. Z = number of rollers.
CountFit FitRollerCount(const CageAverage& average,
                        const SpinSidebands* sidebands,
                        int z,
                        const CountFitOptions& options = {});

// H(x) of a shape, smoothed, for a bin of width bin_rad (what the fit uses; exposed for tests).
double SmoothedHump(double x, const HumpShape& shape, double bin_rad);

// Roller `roller`'s term a_k H(phi_bin - theta_0 + 2 pi s_k / Z) of feature A's model at a bin
// of the average (the model is the floor plus the sum of these).
double RollerHump(const CageAverage& average, const HumpFit& fit, int z, size_t roller, int bin);

// Feature B's chi2 of one configuration (its slots, strengths, theta_0 and shape from feature
// A), minimised over the spin phases, strength ratios, a hump offset and two shapes as described
// above (with pattern_per_parity: over the spin phases and strength ratios with the patterns per
// parity; with second_pattern: with the second pattern per roller as well); *parameters receives
// its parameter count. Exposed for tests.
// *spin_phase (may be null) receives phi_k (phi_1 = 0).
double SidebandChi2(const SpinSidebands& sidebands,
                    const HumpFit& fit,
                    int z,
                    int* parameters,
                    std::vector<double>* spin_phase = nullptr,
                    bool pattern_per_parity = false,
                    bool second_pattern = false);

// Fourier coefficients M_m = (1/2 pi) int H(x) cos(m x) dx, m = 0..orders (H without bin width).
std::vector<double> HumpFourier(const HumpShape& shape, int orders);

}  // namespace spallkit::identify
