#include "dsp/explain.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>
#include <utility>

#include "core/error.h"

namespace spallkit::dsp {

bool ExplanationOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* m) {
    if (error) *error = m;
    return false;
  };
  if (!(match_bins >= 0.5 && match_bins <= 10.0)) return fail("match bins must be in [0.5, 10]");
  if (!(window_bins >= 0.5 && window_bins <= 20.0)) return fail("window bins must be in [0.5, 20]");
  if (sideband_orders < 0 || sideband_orders > 5) return fail("sideband orders must be in 0..5");
  if (!(integer_ratio_tolerance >= 0.0 && integer_ratio_tolerance < 0.5))
    return fail("integer ratio tolerance must be in [0, 0.5)");
  if (!(roller_cage_resolution_bins >= 0.0 && roller_cage_resolution_bins <= 100.0))
    return fail("roller/cage resolution bins must be in [0, 100]");
  return true;
}

namespace {

const FaultFamily* FindFamily(const std::vector<FaultFamily>& families, FaultComponent c) {
  for (const auto& f : families)
    if (f.component == c) return &f;
  return nullptr;
}

int HarmonicCount(const FaultFamily& family) {
  int n = 0;
  for (const auto& l : family.lines) n = std::max(n, l.harmonic);
  return n;
}

// The strongest bin within `match` bins of f when it is a local maximum (a window edge that is
// only the shoulder of a line outside does not count); -1 otherwise.
int PeakNear(const NormalizedSpectrum& s, double f, double match) {
  const double df = s.resolution_hz;
  const int n = static_cast<int>(s.power.size());
  const int lo = std::max(1, static_cast<int>(std::ceil(f / df - match)));
  const int hi = std::min(n - 2, static_cast<int>(std::floor(f / df + match)));
  if (lo > hi) return -1;
  int best = lo;
  for (int i = lo + 1; i <= hi; ++i)
    if (s.power[i] > s.power[best]) best = i;
  if (s.power[best] < s.power[best - 1] || s.power[best] < s.power[best + 1]) return -1;
  return best;
}

// Cage rate refined on its own harmonics k f_c, k = 1..K, walking upward: each significant peak
// found within the match window updates the least-squares rate, so the prediction for the next
// harmonic carries the accumulated precision (a 0.1 % rate error is a bin at the 60th harmonic).
double RefineRate(const NormalizedSpectrum& s,
                  double f0,
                  double max_hz,
                  const DetectionOptions& options,
                  const ExplanationOptions& explanation) {
  if (!(f0 > 0.0)) return f0;
  double num = 0.0, den = 0.0, rate = f0;
  for (int k = 1; k * rate <= max_hz; ++k) {
    const int i = PeakNear(s, k * rate, explanation.match_bins);
    if (i < 0 || s.PairPValue(s.z[i]) > options.line_p_value) continue;
    const double f = InterpolatePeakHz(s.power, i, s.resolution_hz);
    num += k * f;
    den += double(k) * k;
    rate = num / den;
  }
  return rate;
}

// The roller forest's lowest line, BSF - (sideband_orders + 1/2) f_c: below it a line at an
// integer multiple of f_c is a cage-rate line, above it may be a (k - 1/2) f_b +/- m f_c one.
double RollerForestFloorHz(double f_b_hz, double f_c_hz, int sideband_orders) {
  return 0.5 * f_b_hz - (sideband_orders + 0.5) * f_c_hz;
}

// The significant lower and upper sidebands of harmonic line h (null where there is none).
std::pair<const LineEvidence*, const LineEvidence*> SignificantSidebands(const FamilyDetection& det,
                                                                         const LineEvidence& h) {
  const LineEvidence *lo = nullptr, *hi = nullptr;
  if (h.line.half_order) return {lo, hi};  // the spin series carries no sidebands of its own here
  for (const auto& sb : det.lines) {
    if (!sb.line.is_sideband() || sb.line.harmonic != h.line.harmonic || !sb.significant) continue;
    (sb.line.sideband < 0 ? lo : hi) = &sb;
  }
  return {lo, hi};
}

}  // namespace

FamilyRates MeasureRates(const FamilyDetection& det,
                         const FaultFamily& family,
                         double cage_hz,
                         double shaft_hz) {
  FamilyRates r;
  r.fundamental_hz = det.fundamental_hz;
  switch (family.component) {
    case FaultComponent::kOuterRace:
      r.sideband_hz = cage_hz * det.scale;
      break;
    case FaultComponent::kInnerRace:
      r.sideband_hz = shaft_hz > 0.0 ? shaft_hz : family.sideband_hz * det.scale;
      break;
    case FaultComponent::kCage:
      r.sideband_hz = 0.0;
      break;
    case FaultComponent::kRollingElement: {
      r.sideband_hz = cage_hz * det.scale;
      double sum = 0.0;
      int count = 0;
      for (const auto& h : det.lines) {
        if (h.line.is_sideband() || h.excluded) continue;
        const auto [lo, hi] = SignificantSidebands(det, h);
        if (lo && hi) {
          sum += 0.5 * (hi->freq_hz - lo->freq_hz);
          ++count;
        }
      }
      if (count == 0) {
        // No harmonic with both sidebands (e.g. its carrier excluded as a shaft line): single
        // significant sidebands against the measured k f_b.
        for (const auto& sb : det.lines) {
          if (!sb.line.is_sideband() || !sb.significant) continue;
          sum += sb.line.sideband * (sb.freq_hz - sb.line.harmonic * det.fundamental_hz);
          ++count;
        }
      }
      if (count > 0) {
        r.sideband_hz = sum / count;
        r.sideband_measured = true;
      }
      break;
    }
  }
  return r;
}

std::string CageRateMeasurement::Source() const {
  std::string out;
  auto part = [&](int n, const char* one, const char* many) {
    if (n == 0) return;
    if (!out.empty()) out += " + ";
    out += std::to_string(n) + " " + (n == 1 ? one : many);
  };
  part(sideband_pairs, "sideband pair", "sideband pairs");
  part(modulation_lines, "modulation line", "modulation lines");
  part(single_sidebands, "single sideband", "single sidebands");
  return out.empty() ? "none" : out;
}

CageRateMeasurement MeasureRollerCageRate(const NormalizedSpectrum& s,
                                          const FamilyDetection& det,
                                          const FaultFamily& family,
                                          double cage_hz,
                                          double shaft_hz,
                                          const DetectionOptions& options,
                                          const ExplanationOptions& explanation) {
  CageRateMeasurement out;
  if (family.component != FaultComponent::kRollingElement || !(cage_hz > 0.0)) return out;
  double num = 0.0, den = 0.0;  // sum w e, sum w over the estimates e
  auto add = [&](double estimate, double weight) {
    num += weight * estimate;
    den += weight;
  };
  // Sideband pairs around a harmonic: (f_hi - f_lo) / (m_hi - m_lo), the error of two peaks over
  // (m_hi - m_lo), i.e. weight (m_hi - m_lo)^2 / 2.
  for (const auto& h : det.lines) {
    if (h.line.is_sideband() || h.excluded) continue;
    const auto [lo, hi] = SignificantSidebands(det, h);
    if (!lo || !hi) continue;
    const double orders = hi->line.sideband - lo->line.sideband;
    add((hi->freq_hz - lo->freq_hz) / orders, 0.5 * orders * orders);
    ++out.sideband_pairs;
  }
  // Modulation lines m f_c, walking upward from the best rate so far.
  const double df = s.resolution_hz;
  const double shaft_base = shaft_hz / std::max(1, options.shaft_order_divisor);
  auto resolved = [&](double f) {
    if (DistanceToHarmonic(f, shaft_base) <= df) return false;
    for (double mains : options.mains_hz)
      if (DistanceToHarmonic(f, mains) <= df) return false;
    return true;
  };
  double rate = den > 0.0 ? num / den : cage_hz * det.scale;
  const double forest_floor_hz =
      RollerForestFloorHz(det.fundamental_hz, rate, explanation.sideband_orders);
  for (int m = 1; m * rate < forest_floor_hz; ++m) {
    const int i = PeakNear(s, m * rate, explanation.match_bins);
    if (i < 0 || s.PairPValue(s.z[i]) > options.line_p_value) continue;
    const double f = InterpolatePeakHz(s.power, i, df);
    if (!resolved(f)) continue;
    add(f / m, double(m) * m);
    ++out.modulation_lines;
    rate = num / den;
  }
  if (den == 0.0) {
    for (const auto& sb : det.lines) {
      if (!sb.line.is_sideband() || !sb.significant) continue;
      add((sb.freq_hz - sb.line.harmonic * det.fundamental_hz) / sb.line.sideband, 1.0);
      ++out.single_sidebands;
    }
  }
  if (den > 0.0) out.hz = num / den;
  return out;
}

std::vector<double> PredictedLines(FaultComponent component,
                                   const FamilyRates& rates,
                                   int harmonics,
                                   int sideband_orders,
                                   double max_hz) {
  std::vector<double> out;
  const double f0 = rates.fundamental_hz, fsb = rates.sideband_hz;
  if (!(f0 > 0.0)) return out;
  auto add = [&](double f) {
    if (f > 0.0 && f <= max_hz) out.push_back(f);
  };
  auto cluster = [&](double centre) {
    add(centre);
    if (fsb > 0.0)
      for (int m = 1; m <= sideband_orders; ++m) {
        add(centre - m * fsb);
        add(centre + m * fsb);
      }
  };
  switch (component) {
    case FaultComponent::kOuterRace:
    case FaultComponent::kInnerRace:
      for (int k = 1; k <= harmonics; ++k) cluster(k * f0);
      break;
    case FaultComponent::kRollingElement:
      for (int k = 1; k <= harmonics; ++k) {
        cluster(k * f0);
        cluster((k - 0.5) * f0);  // 1 x BSF series: alternating outer/inner race hits
      }
      // The load-zone modulation itself: the spall passes the load zone once per cage turn.
      if (fsb > 0.0)
        for (int m = 1; m <= harmonics; ++m) add(m * fsb);
      break;
    case FaultComponent::kCage:
      for (int k = 1; k * f0 <= max_hz; ++k) add(k * f0);
      break;
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<ExplainedLine> ClaimLines(const NormalizedSpectrum& spectrum,
                                      const std::vector<double>& predicted_hz,
                                      FaultComponent by,
                                      const DetectionOptions& options,
                                      const ExplanationOptions& explanation) {
  std::vector<ExplainedLine> out;
  const double df = spectrum.resolution_hz;
  for (double f : predicted_hz) {
    const int i = PeakNear(spectrum, f, explanation.match_bins);
    if (i < 0) continue;
    const double p = spectrum.PairPValue(spectrum.z[i]);
    if (p > options.line_p_value) continue;
    bool seen = false;
    for (const auto& e : out) seen |= e.bin == i;
    if (seen) continue;
    ExplainedLine e;
    e.bin = i;
    e.freq_hz = InterpolatePeakHz(spectrum.power, i, df);
    e.half_width_hz = explanation.window_bins * df + options.guard_fraction * e.freq_hz;
    e.score = std::min(-std::log(std::max(p, 1e-300)), options.max_line_score);
    e.by = by;
    out.push_back(e);
  }
  return out;
}

namespace {

// Mean uncapped -ln p of `det`'s non-excluded harmonics away from every multiple of other_hz,
// and how many of those are significant.
std::pair<double, int> UnsharedEvidence(const FamilyDetection& det,
                                        double other_hz,
                                        double df,
                                        const DetectionOptions& options,
                                        const ExplanationOptions& explanation) {
  double sum = 0.0;
  int count = 0, significant = 0;
  for (const LineEvidence& e : det.lines) {
    if (e.line.is_sideband() || e.excluded) continue;
    const double window = explanation.window_bins * df + options.guard_fraction * e.freq_hz;
    if (other_hz > 0.0 && DistanceToHarmonic(e.freq_hz, other_hz) <= window) continue;
    sum += -std::log(std::max(e.p_value, 1e-300));
    ++count;
    significant += e.significant;
  }
  return {count > 0 ? sum / count : 0.0, significant};
}

}  // namespace

RaceSeparation SeparateRaces(const FamilyDetection& outer,
                             const FamilyDetection& inner,
                             double resolution_hz,
                             const DetectionOptions& options,
                             const ExplanationOptions& explanation) {
  RaceSeparation r;
  r.tested = true;
  std::tie(r.outer_evidence, r.outer_significant) =
      UnsharedEvidence(outer, inner.fundamental_hz, resolution_hz, options, explanation);
  std::tie(r.inner_evidence, r.inner_significant) =
      UnsharedEvidence(inner, outer.fundamental_hz, resolution_hz, options, explanation);
  r.separable = r.outer_significant > 0 || r.inner_significant > 0;
  return r;
}

std::string RollerCageSeparation::Describe() const {
  char buf[320];
  std::snprintf(buf,
                sizeof buf,
                "rolling element and cage comb not separable: the bearing's f_b lies %.3g Hz "
                "(%.2g SES bins) from the nearest cage harmonic, too close for this record's "
                "resolution to tell a roller comb from a cage comb by their rates",
                offset_hz,
                offset_bins);
  return buf;
}

std::string RaceSeparation::Describe() const {
  char buf[256];
  std::snprintf(buf,
                sizeof buf,
                "outer and inner race not separable: no significant harmonic of either lies away "
                "from the other's comb (unshared evidence outer %.1f, inner %.1f)",
                outer_evidence,
                inner_evidence);
  return buf;
}

JointExplanation ExplainJointly(const NormalizedSpectrum& spectrum,
                                const std::vector<FaultFamily>& families,
                                std::vector<FamilyDetection> detections,
                                const DetectionContext& context,
                                const DetectionOptions& options,
                                const ExplanationOptions& explanation) {
  std::string error;
  if (!explanation.IsValid(&error)) throw InputError("explanation: " + error);
  if (detections.size() != families.size())
    throw InputError("explanation: one detection per family expected");
  JointExplanation out;
  const FaultFamily* cage_family = FindFamily(families, FaultComponent::kCage);
  const double cage_hz = cage_family ? cage_family->fundamental_hz : 0.0;
  const double shaft_hz =
      context.shaft_hz * (context.measured_shaft_scale > 0.0 ? context.measured_shaft_scale : 1.0);
  const double max_hz = (static_cast<int>(spectrum.power.size()) - 2) * spectrum.resolution_hz;

  // Is the roller comb only a dense cage comb? (see the header)
  out.roller_integer_ratio_mismatch = std::numeric_limits<double>::quiet_NaN();
  // The cage rate for the integer test: the least-squares rate through the sub-bin peak
  // positions of a detected cage comb's significant harmonics, sum m f_m / sum m^2. Its error
  // is the peak error over the highest order (~0.1 % at 0.5-1 Hz bins), whereas the half-distance
  // of the roller comb's sideband pairs and the comb search's speed grid scatter by 0.5-1 %, as
  // much as the test's tolerance (N205EM: f_b / f_c = 13.85, 1.1 % from 14). (Not RefineRate:
  // followed up to high orders, the cage series locks onto a roller forest's lines, 14 f_c onto
  // f_b, and makes any roller comb an integer multiple.)
  // Only cage orders below the roller forest's lowest line, BSF - (sideband_orders + 1/2) f_c
  // (N205EM: 4.4 f_c, 6205: 3.4 f_c), count: above it a forest line (k - 1/2) f_b +/- m f_c sits
  // within 0.1 f_c of a cage order and the comb search may take it for the cage harmonic.
  double forest_floor_hz = std::numeric_limits<double>::infinity();
  for (const FaultFamily& f : families)
    if (f.component == FaultComponent::kRollingElement && cage_hz > 0.0)
      forest_floor_hz = RollerForestFloorHz(f.fundamental_hz, cage_hz, explanation.sideband_orders);
  double cage_measured_hz = 0.0;
  const FamilyDetection* cage_det = nullptr;
  for (size_t i = 0; i < families.size(); ++i) {
    if (families[i].component != FaultComponent::kCage || !detections[i].detected) continue;
    cage_det = &detections[i];
    double num = 0.0, den = 0.0;
    int used = 0;
    for (const LineEvidence& e : detections[i].lines)
      if (e.significant && !e.excluded && e.line.sideband == 0 && e.line.harmonic > 0 &&
          e.line.harmonic * cage_hz < forest_floor_hz)
        num += e.line.harmonic * e.freq_hz, den += double(e.line.harmonic) * e.line.harmonic,
            ++used;
    if (used >= 2) cage_measured_hz = num / den;
  }
  for (size_t i = 0; i < families.size(); ++i) {
    if (families[i].component != FaultComponent::kRollingElement || !detections[i].detected)
      continue;
    if (cage_det && cage_hz > 0.0) {
      // Can the record tell this bearing's roller comb from a cage comb at all?
      const double f_b = families[i].fundamental_hz;
      RollerCageSeparation& sep = out.roller_cage;
      sep.tested = true;
      sep.offset_hz = std::abs(f_b - std::max(1.0, std::round(f_b / cage_hz)) * cage_hz);
      sep.offset_bins = sep.offset_hz / spectrum.resolution_hz;
      sep.separable = sep.offset_bins >= explanation.roller_cage_resolution_bins;
    }
    const FamilyRates r = MeasureRates(detections[i], families[i], cage_hz, shaft_hz);
    const double fsb = cage_measured_hz > 0.0 ? cage_measured_hz
                       : r.sideband_measured  ? r.sideband_hz
                                              : 0.0;
    if (!(fsb > 0.0)) continue;
    const double ratio = r.fundamental_hz / fsb;
    const double n = std::max(1.0, std::round(ratio));
    out.roller_integer_ratio_mismatch = ratio / n - 1.0;
    // A cage comb sits ON the integer; a roller comb near the bearing's own f_b / f_c (slip moves
    // both rates together). Call it a cage comb only when the integer is also the nearer one.
    const double kinematic_ratio = cage_hz > 0.0 ? families[i].fundamental_hz / cage_hz
                                                 : std::numeric_limits<double>::infinity();
    const bool on_integer =
        std::abs(out.roller_integer_ratio_mismatch) <= explanation.integer_ratio_tolerance &&
        std::abs(ratio - n) < std::abs(ratio - kinematic_ratio);
    // The ratio may sit on the integer by its measurement error (unresolved records) or by the
    // cage slipping more than the rollers, and a roller spall's load-zone lines may outweigh its
    // f_b harmonics: the detected roller comb is taken for a dense cage comb only when both say
    // so (see the header).
    out.roller_is_cage_comb =
        on_integer && cage_det && cage_det->harmonic_evidence > detections[i].harmonic_evidence;
  }

  // Outer against inner race on the harmonics only one of them predicts.
  const FamilyDetection* outer_det = nullptr;
  const FamilyDetection* inner_det = nullptr;
  for (const FamilyDetection& det : detections) {
    if (!det.detected) continue;
    if (det.component == FaultComponent::kOuterRace) outer_det = &det;
    if (det.component == FaultComponent::kInnerRace) inner_det = &det;
  }
  if (outer_det && inner_det)
    out.races = SeparateRaces(*outer_det, *inner_det, spectrum.resolution_hz, options, explanation);

  auto explains_first = [&](const FamilyDetection& a, const FamilyDetection& b) {
    using C = FaultComponent;
    const bool rc = a.component == C::kRollingElement && b.component == C::kCage;
    const bool cr = a.component == C::kCage && b.component == C::kRollingElement;
    if (rc) return !out.roller_is_cage_comb;
    if (cr) return out.roller_is_cage_comb;
    const bool oi = a.component == C::kOuterRace && b.component == C::kInnerRace;
    const bool io = a.component == C::kInnerRace && b.component == C::kOuterRace;
    if ((oi || io) && out.races.separable && out.races.outer_evidence != out.races.inner_evidence)
      return oi == (out.races.outer_evidence > out.races.inner_evidence);
    if (a.harmonic_evidence != b.harmonic_evidence)
      return a.harmonic_evidence > b.harmonic_evidence;
    return a.p_value < b.p_value;
  };

  DetectionContext ctx = context;
  std::vector<int> remaining;
  for (size_t i = 0; i < detections.size(); ++i) remaining.push_back(static_cast<int>(i));
  while (true) {
    int pick = -1;
    for (int i : remaining)
      if (detections[i].detected && (pick < 0 || explains_first(detections[i], detections[pick])))
        pick = i;
    if (pick < 0) break;
    remaining.erase(std::find(remaining.begin(), remaining.end(), pick));
    const FamilyDetection& det = detections[pick];
    const FaultFamily& fam = families[pick];
    FamilyRates rates = MeasureRates(det, fam, cage_hz, shaft_hz);
    if (fam.component == FaultComponent::kCage)
      rates.fundamental_hz =
          RefineRate(spectrum, rates.fundamental_hz, max_hz, options, explanation);
    const auto predicted = PredictedLines(
        fam.component, rates, HarmonicCount(fam), explanation.sideband_orders, max_hz);
    const auto claims = ClaimLines(spectrum, predicted, fam.component, options, explanation);
    out.ranked.push_back(det);
    out.explained.insert(out.explained.end(), claims.begin(), claims.end());
    ctx.explained.insert(ctx.explained.end(), claims.begin(), claims.end());
    for (int r : remaining) detections[r] = DetectFamily(spectrum, families[r], ctx, options);
  }
  std::vector<FamilyDetection> rest;
  for (int i : remaining) rest.push_back(detections[i]);
  std::stable_sort(rest.begin(), rest.end(), [](const auto& a, const auto& b) {
    if (a.p_value != b.p_value) return a.p_value < b.p_value;
    return a.score - a.threshold > b.score - b.threshold;
  });
  out.ranked.insert(out.ranked.end(), rest.begin(), rest.end());
  return out;
}

}  // namespace spallkit::dsp
