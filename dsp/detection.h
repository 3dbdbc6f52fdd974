// Fault-family detection in a squared envelope spectrum with a controlled false-alarm rate.
//
// Why not "is there a peak near BPFO?": healthy machines show SES lines at shaft harmonics, at
// mains harmonics (50/60 Hz families), and even at the BPFO order; nominal speeds are off by a few
// percent. Peak look-ups flag between a fifth and all healthy channels. The statistic here rests on
// (1) a harmonic FAMILY whose lines move together, (2) significance of each line against the local
// noise floor, (3) an analytic null distribution with a stated family-wise false-alarm rate.
//
// Model. For Gaussian noise in the demodulation band the SES power P(a) = |FFT(SE - mean)|^2 at a
// cyclic frequency a is ~ exponential around its local mean mu(a) (chi^2 with 2 dof). mu(a) is
// estimated robustly by a running median of the neighbouring bins divided by ln 2 (median of an
// exponential = ln 2 x mean); z = P / mu. Because mu is itself estimated from W bins, the bin tail
// is the Lomax law P(z > t) = (1 + t/n)^-n with n = W ln^2 2 (the median's efficiency), not e^-t.
//
// Comb. For a family with kinematic lines f_l (harmonics k f0 and sidebands k f0 +/- f_sb) all
// lines move with one speed-scale factor s in [c (1 - tol), c (1 + tol)] (c = 1, or the measured
// shaft speed / nominal when known). On a grid fine enough that the highest line moves <= 1/2 bin
// per step, each line takes the larger z of the two bins around s f_l; its p-value is p = 1 - (1 -
// q)^2 with q the Lomax tail. The comb score is S(s) = sum_l min(-ln p_l, cap): under the null -ln
// p_l ~ Exp(1), independent across lines, so S ~ Gamma(M, 1) with M lines used (the cap only makes
// the test conservative). The family statistic is max_s S(s); its p-value is Bonferroni-corrected
// by the number C of distinct bin combinations the grid visits and by the caller's multiplicity
// (families x candidate bands):  p = min(1, mult C Q(M, S)), Q the regularised upper incomplete
// gamma. Detected iff p <= false_alarm_probability AND the evidence is a family: >= 2 harmonics
// individually significant (p_l <= line_p_value), or one harmonic together with both of its
// expected sidebands; for the rolling element also 3 lines of f_b and its spin series (k - 1/2)
// f_b with at least one of each, or one f_b harmonic and 2 more lines no bare f_b comb has (f_c
// sidebands of any harmonics, spin-series lines; several defective rollers' sidebands cancel on
// one side; FamilyDetection::family_evidence).
// Lines that coincide with a shaft harmonic (m f_r, at the comb's speed and at
// the measured speed) or a mains harmonic (m 50, m 60 Hz) are excluded from the evidence (neither
// counted nor scored): any machine has them.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "dsp/fault_bands.h"
#include "dsp/gamma_tail.h"
#include "dsp/noise_floor.h"

namespace spallkit::dsp {

struct DetectionOptions {
  double false_alarm_probability = 1e-3;  // family-wise, per record (after all corrections)
  double tolerance = 0.02;                // speed-scale search half-width (relative)
  int floor_window_bins = 401;            // running-median window (bins, centred where possible)
  double line_p_value = 1e-3;             // a line is "individually significant" below this
  double max_line_score = 25.0;           // cap on -ln p of a single line
  std::vector<double> mains_hz = {50.0, 60.0};
  double guard_bins = 2.0;        // exclusion half-width around shaft/mains harmonics, in bins...
  double guard_fraction = 0.002;  // ...or this fraction of the line frequency, whichever is larger
  // Shaft lines are excluded at multiples of f_r / shaft_order_divisor: 2 also treats the
  // half orders (m + 1/2) f_r of looseness and rub as non-evidence (CWRU's healthy record 97
  // has strong 16.5 and 27.5 order lines in its SES).
  int shaft_order_divisor = 2;
  // Families whose physics predicts sidebands (inner race: +/- f_r from the load zone; rolling
  // element: +/- f_c) must show at least this many significant sidebands besides >= 2
  // harmonics: a bare harmonic comb at 5.4 orders is what CWRU's healthy record 97 has.
  int min_sidebands = 2;
  // A shaft/mains-excluded line is tested against its nuisance comb only when that comb has at
  // least this many reference lines (in the searched range, outside every scored line's search
  // window of the family: the spin series is not scored) to take the strongest from.
  int min_nuisance_references = 3;
  // Effect size: a significant line must also modulate at least this fraction of the band's
  // mean squared envelope (level / mean(SE); an AM depth m gives m, a sharp impulse train ~1 per
  // harmonic). Significance alone grows with record length, and every bearing has weak
  // BPFO-order lines (varying compliance); those modulate a few % at most. Needs
  // NormalizedSpectrum::envelope_mean > 0, else only p-values count.
  double min_modulation = 0.12;

  bool IsValid(std::string* error) const;
};

// Running median / ln 2 over `options.floor_window_bins` bins (dsp/noise_floor.h), after the
// options are validated.
NormalizedSpectrum NormalizeSpectrum(std::span<const double> power,
                                     double resolution_hz,
                                     const DetectionOptions& options = {});

struct LineEvidence {
  FaultLine line;
  double freq_hz = 0.0;     // sub-bin peak position near s f_l
  double power = 0.0;       // SES power at the line (the larger of the two bins)
  double z = 0.0;           // power / floor
  double p_value = 1.0;     // per-line null p-value
  double modulation = 0.0;  // level / mean squared envelope (0 when unknown)
  bool significant = false;
  bool excluded = false;  // coincides with a shaft or mains harmonic, or beyond the spectrum
  std::string exclusion;  // "shaft", "mains", "range", "" otherwise
  // A line excluded as "shaft" or "mains" is left out of the comb score, but it still counts in
  // the family rule when it stands out of its nuisance comb: z is then tested against the
  // strongest line of the same shaft-order / mains comb elsewhere in the searched range
  // (nuisance_z >= 1): z is the largest within +/- 1.5 bins of the line and p_value = 1 - (1 -
  // q)^4 with q the bin tail of z / nuisance_z. 0: not tested (too few reference lines).
  double nuisance_z = 0.0;
};

// An SES line accounted for by a detected family: its measured (sub-bin) position and the
// half-width of the window in which other families' lines count as the same line.
struct ExplainedLine {
  double freq_hz = 0.0;
  double half_width_hz = 0.0;
  double score = 0.0;  // capped -ln p of the line (its evidence)
  int bin = 0;         // the SES bin of its peak
  FaultComponent by = FaultComponent::kOuterRace;
};

// Where the search is centred and how many tests the caller makes in total.
struct DetectionContext {
  double shaft_hz = 0.0;            // nominal shaft speed f_r
  double center_scale = 1.0;        // comb search centre c (measured speed / nominal)
  double measured_shaft_scale = 0;  // > 0: also exclude shaft harmonics at this speed
  double multiplicity = 1.0;        // families x candidate bands (Bonferroni)
  bool exclude_shaft = true;        // false to search for the shaft harmonics themselves
  bool exclude_mains = true;
  // Further fundamentals (Hz) whose harmonics are non-evidence, e.g. a detected cage rate: a
  // cage fault's dense f_c comb would otherwise also feed the f_b (~ 12 f_c for a 6205) and
  // BPFO (= Z f_c) combs. Reported as exclusion "cage".
  std::vector<double> exclude_harmonics_of_hz;
  // Lines already explained by a family ranked higher (joint explanation, dsp/explain.h): a comb
  // line within half_width_hz of one of them is non-evidence, reported with the explaining
  // family's name as its exclusion.
  std::vector<ExplainedLine> explained;
};

struct FamilyDetection {
  FaultComponent component = FaultComponent::kOuterRace;
  bool detected = false;
  double score = 0.0;           // max over s of the capped sum of -ln p
  double threshold = 0.0;       // score needed for p <= false_alarm_probability
  double p_value = 1.0;         // corrected (comb combinations x multiplicity)
  double scale = 1.0;           // best speed-scale factor s
  double fundamental_hz = 0.0;  // measured fundamental (least squares on significant harmonics,
                                // sub-bin), else s f0
  int lines_used = 0;           // M
  int combinations = 0;         // C
  int significant_harmonics = 0;
  int significant_sidebands = 0;
  // Carrier strength: mean over the non-excluded harmonic lines (not sidebands, not the spin
  // series' half orders) of the uncapped -ln p. Ranks detected families: the lattice of
  // shaft/cage combination lines lets a strong fault feed other combs through sidebands and
  // coincident harmonics (for a 6205, 3 BPFO ~ 2 BPFI), but the true family's own harmonics are
  // the strongest lines.
  double harmonic_evidence = 0.0;
  std::vector<LineEvidence> lines;
  std::string reason;  // why detected / not detected, one line

  bool sidebands_expected = false;
  int min_sidebands = 2;
  bool family_evidence() const;  // the harmonic/sideband rule above
};

// Distance (Hz) from f to the nearest multiple m * base, m >= 1 (infinity for base <= 0). Inline:
// the comb search calls it in its vectorised exclusion pass.
inline double DistanceToHarmonic(double f, double base) {
  if (!(base > 0.0)) return std::numeric_limits<double>::infinity();
  const double m = std::max(1.0, std::nearbyint(f / base));  // ties give equal distances
  return std::abs(f - m * base);
}

FamilyDetection DetectFamily(const NormalizedSpectrum& spectrum,
                             const FaultFamily& family,
                             const DetectionContext& context,
                             const DetectionOptions& options = {});

// Capped -ln PairPValue(max(z[i], z[i+1])) for i = 0 .. bins - 2: the per-line evidence the comb
// scores sum. One vectorised pass per spectrum, shared by every family searched on it.
std::vector<double> PairScores(const NormalizedSpectrum& spectrum,
                               const DetectionOptions& options = {});
// The same, computed only on the half-open runs [first, second) of pairs (the others are 0): the
// pairs some comb plans read (CombSearch::MarkScoredPairs), where a spectrum is searched for
// several families and most of its bins lie in none of their windows.
std::vector<double> PairScores(const NormalizedSpectrum& spectrum,
                               const DetectionOptions& options,
                               std::span<const std::pair<int, int>> runs);

// DetectFamily in two parts, for searching the same family in many spectra of the same
// resolution and size (the diagnosis's candidate bands): the comb plan (speed grid, the bins
// each line visits, the shaft/mains/explained exclusions, the combination count C) depends only
// on the family, the context and the spectrum's size, not on its values, so it is made once;
// Detect() then sums the pair scores along it. DetectFamily(s, f, c, o) ==
// CombSearch(f, c, o, s.resolution_hz, s.z.size()).Detect(s, PairScores(s, o)).
class CombSearch {
 public:
  // Throws InputError for invalid options, a shaft speed <= 0 or a resolution <= 0.
  CombSearch(const FaultFamily& family,
             const DetectionContext& context,
             const DetectionOptions& options,
             double resolution_hz,
             int bins);
  // spectrum must have the planned size and resolution; pair_scores = PairScores(spectrum).
  FamilyDetection Detect(const NormalizedSpectrum& spectrum,
                         std::span<const double> pair_scores) const;
  int bins() const { return nbins_; }
  // Sets (*scored)[b] = 1 for every pair (b, b + 1) that Detect() reads the score of; the other
  // entries of pair_scores may hold anything. scored must hold bins() values.
  void MarkScoredPairs(std::vector<unsigned char>* scored) const;

 private:
  bool Excluded(double f, double s, std::string* why) const;
  // The strongest z among the reference lines of the nuisance combs within the guard of f; 0
  // when f is near none or one of them has too few references.
  double NuisanceLevel(const std::vector<double>& comb_levels,
                       double f,
                       const std::string& exclusion) const;

  // A comb whose lines are non-evidence (shaft orders at the measured or nominal speed, a mains
  // frequency's harmonics), with the SES bins of its lines that no line of the family can
  // occupy: the level a coincident line is compared with.
  struct NuisanceComb {
    double base_hz = 0.0;
    bool shaft = false;
    std::vector<int> reference_bins;  // lower bin of each reference pair
  };
  std::vector<NuisanceComb> nuisance_;

  FaultFamily family_;
  DetectionContext context_;
  DetectionOptions options_;
  double df_ = 0.0;
  int nbins_ = 0;
  double center_ = 1.0;
  std::vector<double> s_grid_;
  std::vector<int> bins_;  // line-major, bins_[l * grid + g]: lower bin of the pair, -1 excluded
  std::vector<int> used_;  // lines used (not excluded) at each grid point
  int combinations_ = 0;   // distinct bin combinations along the grid
  // bins_ as runs of grid points that read the same pair, in line order (scored lines only): the
  // comb scores add one pair score over each run, a contiguous loop.
  struct GridRun {
    int first = 0, last = 0;  // grid points [first, last)
    int bin = 0;              // lower bin of the pair
  };
  std::vector<GridRun> runs_;
};

// The runs [first, second) of pairs that any of plans (all of one size) reads, in order: the
// runs for PairScores(spectrum, options, runs).
std::vector<std::pair<int, int>> ScoredPairRuns(std::span<const CombSearch> plans);

}  // namespace spallkit::dsp
