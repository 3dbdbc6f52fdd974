#include "dsp/detection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.h"
#include "core/multiversion.h"
#include "dsp/vector_math.h"

namespace spallkit::dsp {

bool DetectionOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (!(false_alarm_probability > 0.0 && false_alarm_probability < 1.0))
    return fail("false-alarm probability must be in (0, 1)");
  if (!(tolerance >= 0.0 && tolerance <= 0.2)) return fail("tolerance must be in [0, 0.2]");
  if (floor_window_bins < 21) return fail("floor window must be >= 21 bins");
  if (!(line_p_value > 0.0 && line_p_value < 1.0)) return fail("line p-value must be in (0, 1)");
  if (!(max_line_score > 0.0)) return fail("max line score must be > 0");
  if (!(guard_bins >= 0.0 && guard_fraction >= 0.0)) return fail("guards must be >= 0");
  if (shaft_order_divisor < 1) return fail("shaft order divisor must be >= 1");
  if (min_sidebands < 0) return fail("min sidebands must be >= 0");
  if (!(min_modulation >= 0.0)) return fail("min modulation must be >= 0");
  return true;
}

NormalizedSpectrum NormalizeSpectrum(std::span<const double> power,
                                     double resolution_hz,
                                     const DetectionOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError("detection: " + error);
  return NormalizeSpectrumWindow(power, resolution_hz, options.floor_window_bins);
}

bool FamilyDetection::family_evidence() const {
  if (significant_harmonics >= 2 && (!sidebands_expected || significant_sidebands >= min_sidebands))
    return true;
  // A roller spall's two interleaved series, f_b and the spin series (k - 1/2) f_b (its outer- and
  // inner-race impacts differ), with three lines significant: no race or shaft comb has lines
  // at both, and the f_c sidebands that a single spall's load-zone passage puts around them
  // cancel in part for several defective rollers (their passages are spread over the cage turn).
  int integer_orders = 0, half_orders = 0;
  for (const auto& h : lines) {
    if (h.line.is_sideband() || !h.significant) continue;
    ++(h.line.half_order ? half_orders : integer_orders);
  }
  if (integer_orders >= 1 && half_orders >= 1 && integer_orders + half_orders >= 3) return true;
  // One harmonic with both of its sidebands: a single defect's load-zone modulation.
  for (const auto& h : lines) {
    if (h.line.is_sideband() || h.line.half_order || !h.significant) continue;
    int sb = 0;
    for (const auto& s : lines)
      if (s.line.is_sideband() && s.line.harmonic == h.line.harmonic && s.significant) ++sb;
    if (sb >= 2) return true;
  }
  // Several defective rollers pass the load zone at their own cage angles with their own spin
  // phases, so at each harmonic their f_c sidebands add with other phases on the two sides
  // (j f_b + m f_c: sum over rollers of a_k e^{-i j phi_k} e^{i m 2 pi s_k / Z}) and one side can
  // cancel, and the spin series stands only where the two races' impacts differ: one f_b
  // harmonic and two more lines that no bare f_b comb has, f_c sidebands of any harmonics or
  // spin-series lines.
  return component == FaultComponent::kRollingElement && integer_orders >= 1 &&
         significant_sidebands + half_orders >= min_sidebands;
}

namespace {

// -ln p of the larger of bins (i, i + 1) (NormalizedSpectrum::PairPValue), capped. With
// L = -ln q = n log1p(z / n) (BinTail) and p = q (2 - q): -ln p = L - ln(2 - q), which avoids a
// log of p near 1; the cap is at most -ln 1e-300, as p was floored there. Branch-free with the
// vectorisable log and exp of dsp/vector_math.h (z <= 0 or NaN gives 0; z / n is capped at
// 1e300, where the score is capped anyway), so the loop over the bins vectorises.
inline double PairScoreOf(double z0, double z1, double n_eff, double cap) {
  const double zmax = z0 < z1 ? z1 : z0;  // std::max: NaN in z0 is kept, then gives 0
  const double y = zmax > 0.0 ? std::min(zmax / n_eff, 1e300) : 0.0;
  const double minus_log_q = n_eff * Log1pNonNegative(y);
  const double q = ExpNonPositive(-minus_log_q);
  return std::min(minus_log_q - LogAtLeastOne(2.0 - q), cap);
}

}  // namespace

SPALLKIT_MULTIVERSION
std::vector<double> PairScores(const NormalizedSpectrum& spectrum,
                               const DetectionOptions& options,
                               std::span<const std::pair<int, int>> runs) {
  const int nbins = static_cast<int>(spectrum.z.size());
  const int count = std::max(0, nbins - 1);
  std::vector<double> out(count, 0.0);
  const double n_eff = spectrum.effective_samples;
  const double cap = std::min(options.max_line_score, -std::log(1e-300));
  const double* z = spectrum.z.data();
  for (const auto& [first, last] : runs) {
    SPALLKIT_CHECK(0 <= first && first <= last && last <= count,
                   "pair scores: run [" << first << ", " << last << ") of " << count << " pairs");
    for (int i = first; i < last; ++i) out[i] = PairScoreOf(z[i], z[i + 1], n_eff, cap);
  }
  return out;
}

std::vector<double> PairScores(const NormalizedSpectrum& spectrum,
                               const DetectionOptions& options) {
  const std::pair<int, int> every_pair{0, std::max(0, static_cast<int>(spectrum.z.size()) - 1)};
  return PairScores(spectrum, options, {&every_pair, 1});
}

std::vector<std::pair<int, int>> ScoredPairRuns(std::span<const CombSearch> plans) {
  std::vector<std::pair<int, int>> runs;
  if (plans.empty()) return runs;
  const int bins = plans.front().bins();
  std::vector<unsigned char> scored(bins, 0);
  for (const CombSearch& plan : plans) plan.MarkScoredPairs(&scored);
  for (int b = 0; b < bins;) {
    if (!scored[b]) {
      ++b;
      continue;
    }
    const int first = b;
    while (b < bins && scored[b]) ++b;
    runs.emplace_back(first, b);
  }
  return runs;
}

void CombSearch::MarkScoredPairs(std::vector<unsigned char>* scored) const {
  SPALLKIT_CHECK(static_cast<int>(scored->size()) == nbins_,
                 "comb search: a mask of " << scored->size() << " for " << nbins_ << " bins");
  const int grid = static_cast<int>(s_grid_.size());
  for (size_t l = 0; l < family_.lines.size(); ++l) {
    if (family_.lines[l].half_order) continue;
    const int* bin = bins_.data() + l * grid;
    for (int g = 0; g < grid; ++g)
      if (bin[g] >= 0) (*scored)[bin[g]] = 1;
  }
}

CombSearch::CombSearch(const FaultFamily& family,
                       const DetectionContext& context,
                       const DetectionOptions& options,
                       double resolution_hz,
                       int bins)
    : family_(family), context_(context), options_(options), df_(resolution_hz), nbins_(bins) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError("detection: " + error);
  if (!(context.shaft_hz > 0.0)) throw InputError("detection: shaft speed must be > 0 Hz");
  if (!(resolution_hz > 0.0)) throw InputError("detection: resolution must be > 0 Hz");
  const double df = df_;
  const int nbins = nbins_;
  const double tol = options.tolerance;
  const double c = context.center_scale > 0.0 ? context.center_scale : 1.0;
  center_ = c;
  const double s_lo = c * (1.0 - tol), s_hi = c * (1.0 + tol);
  const int nl = static_cast<int>(family.lines.size());
  const double shaft_base = context.shaft_hz / std::max(1, options.shaft_order_divisor);

  const double f_top = family.MaxLineHz() * s_hi;
  const double ds = f_top > 0.0 ? 0.5 * df / f_top : 1.0;
  const int grid = std::max(1, static_cast<int>(std::ceil((s_hi - s_lo) / ds)) + 1);

  // The walk over s is done line by line over the whole grid, so each step is a short loop the
  // compiler vectorises: f, the guard, the bin, the exclusion tests (as in Excluded(), with
  // each base's reciprocal formed once: multiplying by it can move f/base by an ulp, which
  // changes the rounded harmonic number only at a half-way point, where both neighbours are
  // base/2 away, far outside any guard, so the decisions are the same). None of it depends on
  // the spectrum's values, so it is planned once and kept (bins_) for every band searched.
  s_grid_.resize(grid);
  std::vector<double> comb_hz(grid), comb_inv(grid);
  for (int g = 0; g < grid; ++g) {
    s_grid_[g] = grid == 1 ? c : s_lo + (s_hi - s_lo) * g / double(grid - 1);
    comb_hz[g] = shaft_base * s_grid_[g];
    comb_inv[g] = 1.0 / comb_hz[g];
  }
  std::vector<double> fixed_bases;  // harmonics that do not move with s
  if (context.exclude_shaft)
    fixed_bases.push_back(context.measured_shaft_scale > 0.0
                              ? shaft_base * context.measured_shaft_scale
                              : shaft_base);
  if (context.exclude_mains)
    for (double mains : options.mains_hz) fixed_bases.push_back(mains);
  for (double base : context.exclude_harmonics_of_hz) fixed_bases.push_back(base);
  const double guard_hz = options.guard_bins * df;
  const double guard_fraction = options.guard_fraction;
  const double top_bin = nbins - 1;
  std::vector<double> f(grid), guard(grid), q(grid);
  std::vector<unsigned char> excluded(grid), changed(grid, 0);
  used_.assign(grid, 0);
  bins_.assign(static_cast<size_t>(nl) * grid, -1);
  changed[0] = 1;
  for (int l = 0; l < nl; ++l) {
    // The spin series is tested line by line for the family rule, not scored in the comb: a
    // roller spall whose two races' impacts are alike has none, and its weak lines would only
    // dilute the comb's score. Its bins stay -1 (excluded everywhere).
    if (family.lines[l].half_order) continue;
    const double fl = family.lines[l].nominal_hz;
    for (int g = 0; g < grid; ++g) {
      f[g] = fl * s_grid_[g];
      guard[g] = std::max(guard_hz, guard_fraction * f[g]);
      q[g] = f[g] / df;
      excluded[g] = (q[g] + 1.0 >= top_bin) | (f[g] <= 0.0);  // "range"
    }
    if (context.exclude_shaft) {
      for (int g = 0; g < grid; ++g) {
        const double m = std::max(1.0, std::nearbyint(f[g] * comb_inv[g]));
        excluded[g] |= std::abs(f[g] - m * comb_hz[g]) <= guard[g];
      }
    }
    for (double base : fixed_bases) {
      if (!(base > 0.0)) continue;
      const double inv = 1.0 / base;
      for (int g = 0; g < grid; ++g) {
        const double m = std::max(1.0, std::nearbyint(f[g] * inv));
        excluded[g] |= std::abs(f[g] - m * base) <= guard[g];
      }
    }
    // Lines explained by a family ranked before (usually none reach this line's range).
    for (const ExplainedLine& e : context.explained) {
      if (e.freq_hz + e.half_width_hz < fl * s_lo || e.freq_hz - e.half_width_hz > fl * s_hi)
        continue;
      for (int g = 0; g < grid; ++g) excluded[g] |= std::abs(f[g] - e.freq_hz) <= e.half_width_hz;
    }
    int* bin = bins_.data() + static_cast<size_t>(l) * grid;
    for (int g = 0; g < grid; ++g) bin[g] = excluded[g] ? -1 : static_cast<int>(std::floor(q[g]));
    for (int g = 0; g < grid; ++g) used_[g] += bin[g] >= 0;
    for (int g = 1; g < grid; ++g) changed[g] |= bin[g] != bin[g - 1];
  }
  combinations_ = 0;
  for (int g = 0; g < grid; ++g) combinations_ += changed[g];
  for (int l = 0; l < nl; ++l) {
    if (family.lines[l].half_order) continue;
    const int* bin = bins_.data() + static_cast<size_t>(l) * grid;
    for (int g = 0; g < grid;) {
      const int b = bin[g], first = g;
      while (g < grid && bin[g] == b) ++g;
      if (b >= 0) runs_.push_back({first, g, b});
    }
  }

  // Nuisance combs and their reference lines: every line m * base up to the family's top line
  // that lies outside all of the family's search windows (where it cannot be a fault line).
  auto add_nuisance = [&](double base, bool shaft) {
    if (!(base > 0.0)) return;
    NuisanceComb comb;
    comb.base_hz = base;
    comb.shaft = shaft;
    for (int m = 1; m * base <= f_top; ++m) {
      const double fm = m * base;
      const int bin = static_cast<int>(std::floor(fm / df));
      if (bin + 1.0 >= top_bin) break;
      bool in_window = false;
      for (const FaultLine& line : family.lines) {
        if (line.half_order) continue;  // the spin series is not scored: not a comb window
        const double g = std::max(guard_hz, guard_fraction * fm);
        in_window |= fm >= line.nominal_hz * s_lo - g && fm <= line.nominal_hz * s_hi + g;
      }
      if (!in_window) comb.reference_bins.push_back(bin);
    }
    nuisance_.push_back(std::move(comb));
  };
  if (context.exclude_shaft)
    add_nuisance(
        context.measured_shaft_scale > 0.0 ? shaft_base * context.measured_shaft_scale : shaft_base,
        true);
  if (context.exclude_mains)
    for (double mains : options.mains_hz) add_nuisance(mains, false);
}

double CombSearch::NuisanceLevel(const std::vector<double>& comb_levels,
                                 double f,
                                 const std::string& exclusion) const {
  if (exclusion != "shaft" && exclusion != "mains") return 0.0;
  const double guard = std::max(options_.guard_bins * df_, options_.guard_fraction * f);
  double level = 0.0;
  bool any = false;
  for (size_t c = 0; c < nuisance_.size(); ++c) {
    const NuisanceComb& comb = nuisance_[c];
    // A shaft exclusion may come from the comb's own speed scale: the shaft comb applies.
    if (!(DistanceToHarmonic(f, comb.base_hz) <= guard || (comb.shaft && exclusion == "shaft")))
      continue;
    if (static_cast<int>(comb.reference_bins.size()) < options_.min_nuisance_references) return 0.0;
    level = std::max(level, comb_levels[c]);
    any = true;
  }
  return any ? std::max(level, 1.0) : 0.0;
}

bool CombSearch::Excluded(double f, double s, std::string* why) const {
  const DetectionContext& context = context_;
  const DetectionOptions& options = options_;
  const double df = df_;
  const double shaft_base = context.shaft_hz / std::max(1, options.shaft_order_divisor);
  const double guard = std::max(options.guard_bins * df, options.guard_fraction * f);
  if (context.exclude_shaft &&
      (DistanceToHarmonic(f, shaft_base * s) <= guard ||
       (context.measured_shaft_scale <= 0.0 && DistanceToHarmonic(f, shaft_base) <= guard) ||
       (context.measured_shaft_scale > 0.0 &&
        DistanceToHarmonic(f, shaft_base * context.measured_shaft_scale) <= guard))) {
    if (why) *why = "shaft";
    return true;
  }
  for (double mains : options.mains_hz) {
    if (context.exclude_mains && DistanceToHarmonic(f, mains) <= guard) {
      if (why) *why = "mains";
      return true;
    }
  }
  for (double base : context.exclude_harmonics_of_hz) {
    if (DistanceToHarmonic(f, base) <= guard) {
      if (why) *why = "cage";
      return true;
    }
  }
  for (const ExplainedLine& e : context.explained) {
    if (std::abs(f - e.freq_hz) <= e.half_width_hz) {
      if (why) *why = ComponentName(e.by);
      return true;
    }
  }
  if (f / df + 1.0 >= nbins_ - 1 || f <= 0.0) {
    if (why) *why = "range";
    return true;
  }
  return false;
}

FamilyDetection DetectFamily(const NormalizedSpectrum& spectrum,
                             const FaultFamily& family,
                             const DetectionContext& context,
                             const DetectionOptions& options) {
  const CombSearch search(
      family, context, options, spectrum.resolution_hz, static_cast<int>(spectrum.z.size()));
  return search.Detect(spectrum, PairScores(spectrum, options));
}

FamilyDetection CombSearch::Detect(const NormalizedSpectrum& spectrum,
                                   std::span<const double> pair_scores) const {
  SPALLKIT_CHECK(static_cast<int>(spectrum.z.size()) == nbins_ &&
                     std::abs(spectrum.resolution_hz - df_) <= 1e-12 * df_ &&
                     static_cast<int>(pair_scores.size()) >= nbins_ - 1,
                 "comb search planned for " << nbins_ << " bins of " << df_ << " Hz, given "
                                            << spectrum.z.size() << " of "
                                            << spectrum.resolution_hz);
  const FaultFamily& family = family_;
  const DetectionOptions& options = options_;
  const DetectionContext& context = context_;
  const double df = df_;
  const double c = center_;
  const int nl = static_cast<int>(family.lines.size());
  const int grid = static_cast<int>(s_grid_.size());
  FamilyDetection det;
  det.component = family.component;

  // The comb score of grid point g sums its lines in line order (the runs are in line order, and
  // one line's runs do not overlap).
  std::vector<double> score(grid, 0.0);
  for (const GridRun& run : runs_) {
    const double v = pair_scores[run.bin];
    for (int g = run.first; g < run.last; ++g) score[g] += v;
  }
  const std::vector<int>& used = used_;
  const std::vector<double>& s_grid = s_grid_;
  const int combos = combinations_;

  double best_score = -1.0, best_s = c;
  int best_used = 0;
  double best_tail = 0.0;
  bool best_tail_valid = false;
  for (int g = 0; g < grid; ++g) {
    // Compare combs with different M by their Gamma tail, not the raw sum.
    // Q(M, S) grows with M and falls with S, which settles most comparisons without a tail.
    bool improves;
    if (used[g] == best_used) {
      improves = used[g] > 0 && score[g] > best_score;
    } else if (used[g] > best_used && best_used > 0 && score[g] <= best_score) {
      improves = false;
    } else if (used[g] < best_used && used[g] > 0 && score[g] > best_score) {
      improves = true;
    } else {
      const double better = used[g] > 0 ? -LogGammaUpperTail(used[g], score[g])
                                        : -std::numeric_limits<double>::infinity();
      if (!best_tail_valid) {  // the best comb's tail, formed once per change of the best
        best_tail = best_used > 0 ? -LogGammaUpperTail(best_used, best_score)
                                  : -std::numeric_limits<double>::infinity();
        best_tail_valid = true;
      }
      improves = better > best_tail;
    }
    if (improves) {
      best_score = score[g];
      best_s = s_grid[g];
      best_used = used[g];
      best_tail_valid = false;
    }
  }

  // Ties: where every line of the best comb is capped (a strong fault), many grid points give the
  // same score, and the first of them may sit a bin off the true peaks (on their leakage). The
  // line table is taken at the tied point with the largest uncapped evidence, sum of -ln q, and
  // in the middle of the points that tie on that too (the lines' bins do not pin the scale
  // there; the middle is the scale's best estimate for the lines that do not count).
  if (best_used > 0) {
    const double n_eff = spectrum.effective_samples;
    double best_uncapped = -1.0;
    std::vector<int> tied;
    for (int g = 0; g < grid; ++g) {
      if (used[g] != best_used || score[g] != best_score) continue;
      double uncapped = 0.0;
      for (int l = 0; l < nl; ++l) {
        const int b = bins_[static_cast<size_t>(l) * grid + g];
        if (b >= 0) uncapped += std::log1p(std::max(spectrum.z[b], spectrum.z[b + 1]) / n_eff);
      }
      if (uncapped > best_uncapped) {
        best_uncapped = uncapped;
        tied.clear();
      }
      if (uncapped == best_uncapped) tied.push_back(g);
    }
    if (!tied.empty()) best_s = s_grid[tied[tied.size() / 2]];
  }
  det.scale = best_s;
  det.combinations = combos;
  det.lines_used = best_used;
  det.score = std::max(best_score, 0.0);
  const double mult = std::max(1.0, context.multiplicity) * std::max(1, combos);
  if (best_used > 0) {
    det.threshold = GammaThreshold(best_used, options.false_alarm_probability / mult);
    det.p_value = std::min(1.0, mult * std::exp(LogGammaUpperTail(best_used, det.score)));
  } else {
    det.threshold = std::numeric_limits<double>::infinity();
    det.p_value = 1.0;
  }

  // The strongest reference line of each nuisance comb (z of the larger bin of its pair).
  std::vector<double> comb_levels(nuisance_.size(), 0.0);
  for (size_t c = 0; c < nuisance_.size(); ++c)
    for (int bin : nuisance_[c].reference_bins)
      comb_levels[c] = std::max({comb_levels[c], spectrum.z[bin], spectrum.z[bin + 1]});

  // Line table at the best scale.
  double num = 0.0, den = 0.0;
  auto count_significant = [&](const LineEvidence& ev) {
    if (ev.line.is_sideband()) {
      ++det.significant_sidebands;
    } else {
      ++det.significant_harmonics;
      // Least squares f_k = k f0 with equal errors: f0 = sum k f_k / sum k^2, on the
      // fundamental's own harmonics (the spin series only joins the family rule).
      if (!ev.line.half_order) {
        num += ev.line.harmonic * ev.freq_hz;
        den += double(ev.line.harmonic) * ev.line.harmonic;
      }
    }
  };
  // A line's peak in the table: the strongest of the 4 bins around its position (the pair the
  // comb scored and one more on each side), with p = 1 - (1 - q)^4. Real harmonics are not
  // exactly k s f0 (slip jitter, and the comb's scale is a compromise over all its lines): on a
  // 5 s record a 0.1 % departure at 300 Hz is 1.5 bins.
  const int last_bin = static_cast<int>(std::min(spectrum.power.size(), spectrum.z.size())) - 1;
  auto peak_near = [&](int i0) {
    int i = std::clamp(i0, 0, last_bin);
    for (int j = std::max(0, i0 - 1); j <= std::min(last_bin, i0 + 2); ++j)
      if (spectrum.z[j] > spectrum.z[i]) i = j;
    return i;
  };
  auto window_p_value = [&](double z) {
    return -std::expm1(4.0 * std::log1p(-spectrum.BinTail(z)));
  };
  double harmonic_sum = 0.0;
  int harmonic_count = 0;
  det.lines.reserve(nl);
  for (int l = 0; l < nl; ++l) {
    LineEvidence ev;
    ev.line = family.lines[l];
    const double f = ev.line.nominal_hz * best_s;
    ev.freq_hz = f;
    if (Excluded(f, best_s, &ev.exclusion)) {
      ev.excluded = true;
      const int i0 = static_cast<int>(std::floor(f / df));
      // The other exclusions are tested before "range": a line past the spectrum's end may come
      // back as "shaft" or "mains", so read only bins that exist.
      if (ev.exclusion != "range" && i0 >= 0 && i0 + 1 <= last_bin) {
        int i = spectrum.z[i0 + 1] > spectrum.z[i0] ? i0 + 1 : i0;
        ev.power = spectrum.power[i];
        ev.z = spectrum.z[i];
        // Not scored, but counted in the family rule when it stands out of its nuisance comb.
        ev.nuisance_z = NuisanceLevel(comb_levels, f, ev.exclusion);
        if (ev.nuisance_z > 0.0) {
          i = peak_near(i0);
          ev.power = spectrum.power[i];
          ev.z = spectrum.z[i];
          ev.p_value = window_p_value(ev.z / ev.nuisance_z);
          ev.modulation =
              spectrum.envelope_mean > 0.0 ? std::sqrt(ev.power) / spectrum.envelope_mean : 0.0;
          ev.significant =
              ev.p_value <= options.line_p_value &&
              (spectrum.envelope_mean <= 0.0 || ev.modulation >= options.min_modulation);
          if (ev.significant) {
            ev.freq_hz = InterpolatePeakHz(spectrum.power, i, df);
            count_significant(ev);
          }
        }
      }
      det.lines.push_back(ev);
      continue;
    }
    const int i = peak_near(static_cast<int>(std::floor(f / df)));
    ev.power = spectrum.power[i];
    ev.z = spectrum.z[i];
    ev.p_value = window_p_value(ev.z);
    ev.modulation =
        spectrum.envelope_mean > 0.0 ? std::sqrt(ev.power) / spectrum.envelope_mean : 0.0;
    ev.significant = ev.p_value <= options.line_p_value &&
                     (spectrum.envelope_mean <= 0.0 || ev.modulation >= options.min_modulation);
    ev.freq_hz = InterpolatePeakHz(spectrum.power, i, df);
    // The carrier strength is the fundamental's own harmonics: a dense cage comb also feeds a
    // roller's spin series (BSF = 6.92 f_c on an N205EM, 5.92 f_c on a 6205).
    if (!ev.line.is_sideband() && !ev.line.half_order) {
      harmonic_sum += -std::log(std::max(ev.p_value, 1e-300));
      ++harmonic_count;
    }
    if (ev.significant) count_significant(ev);
    det.lines.push_back(ev);
  }
  det.fundamental_hz = den > 0.0 ? num / den : family.fundamental_hz * best_s;
  det.min_sidebands = options.min_sidebands;
  for (const auto& l : family.lines) det.sidebands_expected |= l.is_sideband();
  det.harmonic_evidence = harmonic_count > 0 ? harmonic_sum / harmonic_count : 0.0;

  const bool significant = det.p_value <= options.false_alarm_probability;
  const bool family_ok = det.family_evidence();
  det.detected = significant && family_ok;
  char buf[256];
  if (det.detected) {
    std::snprintf(buf,
                  sizeof buf,
                  "%d harmonics, %d sidebands significant; p = %.2g <= %.2g",
                  det.significant_harmonics,
                  det.significant_sidebands,
                  det.p_value,
                  options.false_alarm_probability);
  } else if (!significant) {
    std::snprintf(buf,
                  sizeof buf,
                  "comb not significant: p = %.2g > %.2g",
                  det.p_value,
                  options.false_alarm_probability);
  } else {
    std::snprintf(buf,
                  sizeof buf,
                  "significant comb but no family: %d harmonic(s), %d sideband(s) significant",
                  det.significant_harmonics,
                  det.significant_sidebands);
  }
  det.reason = buf;
  return det;
}

}  // namespace spallkit::dsp
