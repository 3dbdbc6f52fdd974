#include "identify/identify.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "core/constants.h"
#include "core/error.h"
#include "core/format.h"
#include "dsp/envelope.h"
#include "identify/line_dft.h"
#include "identify/load_zone.h"
#include "identify/smooth_envelope.h"
#include "sim/quasistatic/harris_jones.h"

namespace spallkit::identify {
namespace {

// The roller rolls sqrt(d delta) past the leading edge before it is released and lands
// sqrt(d delta) before the trailing one (IdentifyOptions::width_contact_release).
double ReleaseAngle(double d, const Identification& id, const IdentifyOptions& o) {
  return o.width_contact_release ? 2.0 * std::sqrt(id.contact_approach_m / d) : 0.0;
}

// The samples (rate fs, from the record's first one) whose cage phase lies in the load zone of
// the fitted humps: the model above 0.3 of its range. With exclusive_ratio > 0 and several humps,
// only where one roller's hump is above 0.3 of its own peak and the others' together are below
// exclusive_ratio of it, both at the sample and `lookahead` samples later (the longest lag the
// autocorrelation pairs it with).
std::vector<char> LoadZoneSamples(const HumpFit& fit,
                                  const CageAverage& average,
                                  int z,
                                  double cage_hz,
                                  double fs,
                                  size_t samples,
                                  double exclusive_ratio,
                                  int lookahead) {
  const int bins = static_cast<int>(fit.model.size());
  std::vector<char> bin_in(bins, 0);
  const auto [lo, hi] = std::minmax_element(fit.model.begin(), fit.model.end());
  const double level = *lo + 0.3 * (*hi - *lo);
  const bool exclusive = exclusive_ratio > 0 && fit.slots.size() > 1;
  if (!exclusive) {
    for (int b = 0; b < bins; ++b) bin_in[b] = fit.model[b] > level;
  } else {
    const size_t k_count = fit.slots.size();
    std::vector<std::vector<double>> hump(k_count, std::vector<double>(bins));
    for (size_t k = 0; k < k_count; ++k)
      for (int b = 0; b < bins; ++b) hump[k][b] = RollerHump(average, fit, z, k, b);
    for (size_t k = 0; k < k_count; ++k) {
      const double peak = *std::max_element(hump[k].begin(), hump[k].end());
      for (int b = 0; b < bins; ++b) {
        double others = 0.0;
        for (size_t j = 0; j < k_count; ++j)
          if (j != k) others += hump[j][b];
        if (hump[k][b] > 0.3 * peak && others <= exclusive_ratio * hump[k][b]) bin_in[b] = 1;
      }
    }
  }
  auto bin_of = [&](size_t i) {
    double turns = i / fs * cage_hz;
    turns -= std::floor(turns);
    return std::min(bins - 1, static_cast<int>(turns * bins));
  };
  std::vector<char> zone(samples);
  for (size_t i = 0; i < samples; ++i)
    zone[i] = bin_in[bin_of(i)] && (!exclusive || bin_in[bin_of(i + lookahead)]);
  return zone;
}

// Feature B's base rate in spin harmonics: the per-parity model works on every spin harmonic.
int SidebandSpinStep(const IdentifyOptions& o) {
  return o.count.sideband_pattern_per_parity ? 1 : o.sideband_spin_step;
}

// Identify's width step for the best configuration of k defective rollers (id's count fit):
// fills id's width fields and returns why no width is stated ("" when it is). sew is the width
// band's smoothed squared envelope at fs, z and d the bearing's roller count and diameter, wo the
// width fit's options for this record.
std::string WidthForCount(int k,
                          const std::vector<double>& sew,
                          double fs,
                          int z,
                          double d,
                          const WidthFitOptions& wo,
                          const IdentifyOptions& options,
                          Identification* id) {
  id->width_fit_exclusive = WidthFit{};
  id->width_from_exclusive_zone = false;
  id->width_identifiable = false;
  id->width_m = id->width_low_m = id->width_high_m = 0.0;
  // Other rollers' impacts fall at fixed lags from one roller's (their spin phases, one
  // impact per half turn each). Those lags are not left out of the fit: a release-landing delay
  // can lie near one, and the fit then still finds it; a delay that lands on one is refused
  // below.
  std::vector<double>& cross_lags = id->other_rollers_lags_s;
  cross_lags.clear();
  if (k >= 2) {
    const std::vector<double>& ph = id->count_fit.best[k].spin_phase_rad;
    const double half_turn = 0.5 / id->spin_hz;
    for (size_t a = 0; a < ph.size(); ++a)
      for (size_t b = a + 1; b < ph.size(); ++b) {
        // phi_k is the spall's phase at feature B's base rate, SidebandSpinStep(options) x f_s.
        double lag = std::fmod(
            (ph[b] - ph[a]) / (2.0 * kPi * SidebandSpinStep(options) * id->spin_hz), half_turn);
        if (lag < 0) lag += half_turn;
        cross_lags.push_back(lag);
        cross_lags.push_back(half_turn - lag);
      }
  }
  const int block = std::max(1, static_cast<int>(fs / id->cage_hz));
  const int lookahead = static_cast<int>(std::ceil((wo.max_delay_s + wo.tail_s) * fs));
  const HumpFit& humps = id->count_fit.best[k];
  // The samples in the load zone: every roller's (others_ratio 0), or where one roller's hump
  // stands out of the others' (LoadZoneSamples).
  auto zone = [&](double others_ratio) {
    return LoadZoneSamples(
        humps, id->cage_average, z, id->cage_hz, fs, sew.size(), others_ratio, lookahead);
  };
  id->width_fit = FitEntryExit(sew, fs, zone(0.0), block, wo);
  // The other rollers' lag nearest to the delay, if it lies within the window.
  std::optional<double> cross_lag;  // the other rollers' lag the delay lies on, if any
  for (double lag : cross_lags) {
    const double off = std::abs(id->width_fit.best.delay_s - lag);
    if (off < options.cross_lag_half_width_s &&
        (!cross_lag || off < std::abs(id->width_fit.best.delay_s - *cross_lag)))
      cross_lag = lag;
  }
  // A delay on another roller's lag is kept when the same pair stands out where each roller has
  // the load zone to itself: there the other rollers' impacts are weak, a release and landing is
  // not (IdentifyOptions::width_exclusive_ratio).
  if (cross_lag && id->width_fit.usable && options.width_exclusive_ratio > 0) {
    // The same pair, judged before its bootstrap (its interval is needed only when it is).
    WidthFitOptions quick = wo;
    quick.bootstrap = 0;
    id->width_fit_exclusive =
        FitEntryExit(sew, fs, zone(options.width_exclusive_ratio), block, quick);
    const WidthFit& x = id->width_fit_exclusive;
    if (x.usable &&
        std::abs(x.best.delay_s - id->width_fit.best.delay_s) < options.cross_lag_half_width_s &&
        x.delay_power_significance >= options.min_delay_significance &&
        x.best.PairPowerRatio() >= options.width_exclusive_min_pair_power_ratio) {
      AddDelayInterval(wo, &id->width_fit_exclusive);
      id->width_fit = id->width_fit_exclusive;
      id->width_from_exclusive_zone = true;
    }
  }
  const WidthFit& wf = id->width_fit;
  auto to_width = [&](double dt) { return WidthOfDelay(dt, d, *id, options); };
  const double spread = 1.645 * options.width_calibration_relative_sd;  // 90 % of the relation's
  const double dt_res = std::max(2.0 / fs, 2.0 * wf.best.rise_s);
  id->width_resolution_m = to_width(dt_res);
  std::string why;
  if (!wf.usable) {
    why = "width: not identifiable (" + wf.message + ")";
  } else if (cross_lag && !id->width_from_exclusive_zone) {
    why = "width: not identifiable (the second event at " +
          FormatNumber("%.2f", wf.best.delay_s * 1e3) + " ms lies on another defective roller's " +
          "impacts (" + FormatNumber("%.2f", *cross_lag * 1e3) +
          " ms from the spin phases): their correlation, not a release and landing" +
          (id->width_fit_exclusive.usable
               ? std::string("; where each roller has the load zone to itself no like pair")
               : std::string()) +
          ")";
  } else if (wf.delay_power_significance < options.min_delay_significance) {
    why = "width: not identifiable (no entry event resolved before the impacts: significance " +
          FormatNumber("%.1f", wf.delay_power_significance) + ")";
  } else if (const double ratio = wf.best.PairPowerRatio();
             ratio < options.min_pair_power_ratio || ratio > options.max_pair_power_ratio) {
    why = "width: not identifiable (the second event at " +
          FormatNumber("%.2f", wf.best.delay_s * 1e3) + " ms correlates at " +
          FormatNumber("%.2f", ratio) + " of the zero-lag power, " +
          (ratio < options.min_pair_power_ratio
               ? "below " + FormatNumber("%.2f", options.min_pair_power_ratio)
               : "above " + FormatNumber("%.2f", options.max_pair_power_ratio)) +
          ": not a release and landing of one roller)";
  } else if (wf.delay_high_s < dt_res) {
    why = "width: below what the record resolves (< " +
          FormatNumber("%.2f", id->width_resolution_m * 1e3) + " mm)";
  } else if (wf.delay_low_s < dt_res) {
    why =
        "width: not identifiable (the entry-exit delay is not resolved from the impact's own "
        "ring-down: the interval reaches below " +
        FormatNumber("%.2f", id->width_resolution_m * 1e3) + " mm)";
  } else {
    id->width_m = to_width(wf.best.delay_s);
    id->width_low_m = to_width(wf.delay_low_s) * (1.0 - spread);
    id->width_high_m = to_width(wf.delay_high_s) * (1.0 + spread);
    const double half = 0.5 * (id->width_high_m - id->width_low_m);
    const double widest = options.width_max_diameter_fraction * d;
    if (id->width_m > widest) {
      why = "width: not identifiable (the fit gives " + FormatNumber("%.2f", id->width_m * 1e3) +
            " mm, wider than the calibration covers: " + FormatNumber("%.2f", widest * 1e3) +
            " mm, " + FormatNumber("%.3g", options.width_max_diameter_fraction) +
            " of the element diameter)";
      id->width_m = id->width_low_m = id->width_high_m = 0.0;
    } else if (half > options.max_width_relative_half_interval * id->width_m) {
      why = "width: not identifiable (90 % interval " +
            FormatNumber("%.2f", id->width_low_m * 1e3) + "-" +
            FormatNumber("%.2f", id->width_high_m * 1e3) + " mm is too wide)";
      id->width_m = id->width_low_m = id->width_high_m = 0.0;
    } else {
      id->width_identifiable = true;
    }
  }
  return why;
}

}  // namespace

double WidthOfDelay(double delay_s, double d, const Identification& id, const IdentifyOptions& o) {
  const double t =
      std::max(0.0, (delay_s - o.width_calibration_offset_s) / o.width_calibration_scale);
  return d * std::sin(std::min(0.5 * kPi, kPi * id.spin_hz * t + ReleaseAngle(d, id, o)));
}

double DelayOfWidth(double width_m, double d, const Identification& id, const IdentifyOptions& o) {
  const double angle = std::asin(std::clamp(width_m / d, 0.0, 1.0)) - ReleaseAngle(d, id, o);
  if (!(angle > 0.0) || !(id.spin_hz > 0.0)) return 0.0;
  return o.width_calibration_scale * angle / (kPi * id.spin_hz) + o.width_calibration_offset_s;
}

std::string CountRefusal(const CountFit& cf, const IdentifyOptions& options) {
  auto argmax = [](const std::vector<double>& p) {
    return static_cast<int>(std::max_element(p.begin(), p.end()) - p.begin());
  };
  const int k = cf.MostProbable();
  if (k == 0)
    return "count: not identifiable (no load-zone hump in the cage-synchronous average: the "
           "impacts are not load-modulated)";
  if (options.count_needs_cage_hump && !cf.probability_cage.empty() &&
      argmax(cf.probability_cage) == 0)
    return "count: not identifiable (the cage-synchronous average by itself shows no load-zone "
           "hump: P(0) = " +
           FormatNumber("%.2f", cf.probability_cage[0]) +
           " from it; the sideband pattern alone does not state a count)";
  if (cf.probability[k] < options.min_count_probability)
    return "count: uncertain (most probable " + std::to_string(k) +
           " with P = " + FormatNumber("%.2f", cf.probability[k]) + ", below the " +
           FormatNumber("%.2f", options.min_count_probability) + " a count needs)";
  if (k < static_cast<int>(cf.best.size())) {
    const HumpShape& shape = cf.best[k].shape;
    auto hump = [&](const std::string& as) {
      return "count: not identifiable (the load-zone hump of " + std::to_string(k) +
             " defective roller" + (k == 1 ? "" : "s") +
             ", P = " + FormatNumber("%.2f", cf.probability[k]) + ", is as " + as;
    };
    if (shape.exponent < options.min_count_hump_exponent) {
      const double edges = shape.EdgeToCentre();
      if (edges < options.flat_hump_max_edge_to_centre)
        return hump("flat as its shape allows (exponent " + FormatNumber("%.2f", shape.exponent) +
                    " < " + FormatNumber("%.2f", options.min_count_hump_exponent) + ", edges " +
                    FormatNumber("%.2f", edges) +
                    " times its centre): wider than one roller's load zone makes it, as the "
                    "merged humps of rollers in adjacent slots are)");
    }
    if (shape.exponent > options.max_count_hump_exponent)
      return hump("narrow as its shape allows (exponent " + FormatNumber("%.2f", shape.exponent) +
                  " > " + FormatNumber("%.2f", options.max_count_hump_exponent) +
                  "): narrower than one roller's load zone makes it, the configuration splits "
                  "strikes between humps rather than following rollers)");
  }
  const bool disagree =
      cf.sideband_lines > 0 && !cf.probability_cage.empty() && !cf.probability_sidebands.empty() &&
      argmax(cf.probability_cage) != argmax(cf.probability_sidebands) &&
      *std::max_element(cf.probability_cage.begin(), cf.probability_cage.end()) > 0.9 &&
      *std::max_element(cf.probability_sidebands.begin(), cf.probability_sidebands.end()) > 0.9;
  if (disagree)
    return "count: not identifiable (cage average says " +
           std::to_string(argmax(cf.probability_cage)) + ", sidebands say " +
           std::to_string(argmax(cf.probability_sidebands)) + ")";
  return "";
}

CountBound LowerCountBound(const CountFit& fit, const IdentifyOptions& options) {
  IdentifyOptions any_probability = options;
  any_probability.min_count_probability = std::numeric_limits<double>::min();
  CountBound bound;
  if (!CountRefusal(fit, any_probability).empty()) return bound;
  double tail = 0.0;
  for (int k = static_cast<int>(fit.probability.size()) - 1; k >= 1; --k) {
    tail += fit.probability[k];
    if (tail >= options.min_count_bound_probability) {
      bound.count = k;
      bound.probability = tail;
      break;
    }
  }
  return bound;
}

bool IdentifyOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (radial_load_n && !(*radial_load_n > 0 && std::isfinite(*radial_load_n)))
    return fail("identify: radial load must be > 0 N");
  if (!(diametral_clearance_m >= 0)) return fail("identify: diametral clearance must be >= 0");
  if (!(roller_length_m >= 0)) return fail("identify: roller length must be >= 0");
  if (cage_bins < 12) return fail("identify: cage_bins must be >= 12");
  if (!(min_count_hump_exponent >= 0 && std::isfinite(min_count_hump_exponent)))
    return fail("identify: min_count_hump_exponent must be >= 0");
  if (!(flat_hump_max_edge_to_centre >= 1 && std::isfinite(flat_hump_max_edge_to_centre)))
    return fail("identify: flat_hump_max_edge_to_centre must be >= 1");
  if (!(max_count_hump_exponent > min_count_hump_exponent &&
        std::isfinite(max_count_hump_exponent)))
    return fail("identify: max_count_hump_exponent must be finite and > min_count_hump_exponent");
  if (min_cage_revolutions < 2) return fail("identify: min_cage_revolutions must be >= 2");
  if (sideband_harmonics < 0 || sideband_orders < 1)
    return fail("identify: sideband_harmonics must be >= 0 and sideband_orders >= 1");
  if (sideband_spin_step != 1 && sideband_spin_step != 2)
    return fail("identify: sideband_spin_step must be 1 (every spin harmonic) or 2 (those of f_b)");
  if (!(min_count_probability > 0 && min_count_probability <= 1))
    return fail("identify: min_count_probability must be in (0, 1]");
  if (!(min_count_bound_probability > 0.5 && min_count_bound_probability <= 1))
    return fail("identify: min_count_bound_probability must be in (0.5, 1]");
  if (!(width_band_min_half_width_hz > 0))
    return fail("identify: width_band_min_half_width_hz must be > 0");
  if (!(width_calibration_scale > 0)) return fail("identify: width calibration scale must be > 0");
  if (!(min_pair_power_ratio >= 0 && max_pair_power_ratio > min_pair_power_ratio))
    return fail("identify: need 0 <= min_pair_power_ratio < max_pair_power_ratio");
  if (!(width_contact_load_fraction > 0 && width_contact_load_fraction <= 1))
    return fail("identify: width_contact_load_fraction must be in (0, 1]");
  if (!(width_calibration_relative_sd >= 0 && width_calibration_relative_sd < 0.5))
    return fail("identify: width calibration scatter must be in [0, 0.5)");
  if (width_max_count < 1) return fail("identify: width_max_count must be >= 1");
  if (!(width_count_min_probability > 0 && width_count_min_probability < 1))
    return fail("identify: width_count_min_probability must be in (0, 1)");
  if (!(width_count_mass > 0 && width_count_mass <= 1))
    return fail("identify: width_count_mass must be in (0, 1]");
  if (!(min_delay_significance >= 0)) return fail("identify: min_delay_significance must be >= 0");
  if (!(max_width_relative_half_interval > 0))
    return fail("identify: max_width_relative_half_interval must be > 0");
  if (!(cross_lag_half_width_s >= 0)) return fail("identify: cross_lag_half_width_s must be >= 0");
  if (!(width_exclusive_ratio >= 0)) return fail("identify: width_exclusive_ratio must be >= 0");
  if (!(width_exclusive_min_pair_power_ratio >= 0))
    return fail("identify: width_exclusive_min_pair_power_ratio must be >= 0");
  if (!(width_max_diameter_fraction > 0 && width_max_diameter_fraction <= 1))
    return fail("identify: width_max_diameter_fraction must be in (0, 1]");
  return count.IsValid(error) && width.IsValid(error);
}

IdentifyOptions SignalModelOptions() {
  IdentifyOptions o;
  o.count.temperature_cage = 1.0;
  o.count.temperature_sidebands = 1.0;
  o.count.min_relative_amplitude = 0.1;
  o.width_contact_release = false;
  o.min_pair_power_ratio = 0.0;
  o.width_exclusive_min_pair_power_ratio = 0.0;
  o.width_calibration_relative_sd = 0.0;
  o.width_max_count = 1 << 20;
  o.width_max_diameter_fraction = 0.8;
  o.sideband_spin_step = 1;
  o.width.shared_ring_down = true;  // both events ring the same resonances
  return o;
}

Identification Identify(const Record& record,
                        const BearingGeometry& bearing,
                        double shaft_hz,
                        const dsp::Diagnosis& diagnosis,
                        const IdentifyOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  bearing.Validate();
  if (!(shaft_hz > 0)) throw InputError("identify: shaft speed must be > 0");
  if (diagnosis.samples != static_cast<int>(record.samples.size()) ||
      std::abs(diagnosis.sample_rate_hz - record.sample_rate_hz) > 1e-9 * record.sample_rate_hz)
    throw InputError("identify: the diagnosis is of another record (" +
                     std::to_string(diagnosis.samples) + " samples at " +
                     FormatNumber("%g", diagnosis.sample_rate_hz) + " Hz, the record has " +
                     std::to_string(record.samples.size()) + " at " +
                     FormatNumber("%g", record.sample_rate_hz) + " Hz)");
  Identification id;
  id.diagnosis = diagnosis;
  id.options = options;
  const std::string depth_reason =
      "depth: not identifiable (the response does not depend on it: docs/IDENTIFY.md)";

  const std::string verdict = dsp::VerdictName(diagnosis.verdict);
  if (diagnosis.verdict != dsp::Verdict::kRollingElement) {
    if (diagnosis.verdict == dsp::Verdict::kOuterRace ||
        diagnosis.verdict == dsp::Verdict::kInnerRace)
      id.reasons.push_back("race fault (" + verdict +
                           "): its impacts carry no roller count and no roller spall width");
    else
      id.reasons.push_back("no roller signature (diagnosis verdict: " + verdict +
                           "): count and width not identifiable");
    id.reasons.push_back(depth_reason);
    return id;
  }
  id.roller_signature = true;

  const double fs = record.sample_rate_hz;
  const double duration = record.duration_s();
  const double d = bearing.element_diameter_m;
  const int z = bearing.num_elements;
  const double f_b0 = diagnosis.measured_f_b_hz.value_or(diagnosis.kinematics.f_b_hz);
  const double f_c0 = diagnosis.measured_f_c_hz.value_or(diagnosis.kinematics.cage_hz * f_b0 /
                                                         diagnosis.kinematics.f_b_hz);

  // Squared envelope in the diagnosis band, alias-free up to the sidebands' highest line.
  dsp::EnvelopeAnalyzer analyzer(record.samples, fs);
  const double needed = 1.2 * (SidebandsHighestLineHz(0.5 * f_b0,
                                                      f_c0,
                                                      options.sideband_harmonics,
                                                      options.sideband_orders,
                                                      SidebandSpinStep(options)) +
                               f_c0);
  double rate = 0.0;
  const std::vector<double> se =
      analyzer.SquaredEnvelope(diagnosis.band, std::max(diagnosis.band.width_hz(), needed), &rate);
  const double half_bin = 0.5 / duration;
  id.cage_hz = RefineRate(
      se, rate, f_c0, diagnosis.measured_f_c_hz ? half_bin : std::max(half_bin, 0.02 * f_c0));
  id.spin_hz = RefineRate(se, rate, 0.5 * f_b0, half_bin, 4);
  id.surface_speed_m_s = kPi * d * id.spin_hz;
  id.cage_revolutions = duration * id.cage_hz;

  // Count and positions.
  CountFitOptions count = options.count;
  if (options.radial_load_n) {
    const double length = options.roller_length_m > 0 ? options.roller_length_m : 1.4 * d;
    const LoadZone zone = SolveLoadZone(
        bearing, *options.radial_load_n, shaft_hz, options.diametral_clearance_m, length);
    count.load_zone_half_angle_rad = zone.half_angle_rad;
    id.load_zone_from_load = true;
    id.roller_load_n = zone.q_max_n;
    // Inner plus outer race approach at the passages' load.
    const double k_c = sim::PalmgrenContactStiffness(length);
    id.contact_approach_m =
        2.0 * sim::PalmgrenApproach(options.width_contact_load_fraction * zone.q_max_n, k_c);
  }
  std::string count_reason, width_reason;
  const bool enough_turns = id.cage_revolutions >= options.min_cage_revolutions;
  if (!enough_turns) {
    count_reason =
        ("count: not identifiable (the record holds " + FormatNumber("%.1f", id.cage_revolutions) +
         " cage revolutions, " + std::to_string(options.min_cage_revolutions) + " needed)");
  } else {
    const int samples_per_turn = static_cast<int>(rate / id.cage_hz);
    id.cage_average =
        AverageOverCage(se, rate, id.cage_hz, std::min(options.cage_bins, samples_per_turn));
    id.sidebands = MeasureSpinSidebands(se,
                                        rate,
                                        id.spin_hz,
                                        id.cage_hz,
                                        options.sideband_harmonics,
                                        options.sideband_orders,
                                        SidebandSpinStep(options));
    id.count_fit = FitRollerCount(id.cage_average, &id.sidebands, z, count);
    const CountFit& cf = id.count_fit;
    id.probabilities = cf.probability;
    id.probabilities_cage = cf.probability_cage;
    if (cf.sideband_lines > 0) id.probabilities_sidebands = cf.probability_sidebands;
    const int k = cf.MostProbable();
    const HumpFit& best = cf.best[k];
    id.load_zone_half_angle_rad = k > 0 ? best.shape.half_angle_rad : 0.0;
    count_reason = CountRefusal(cf, options);
    const CountBound bound = LowerCountBound(cf, options);
    id.count_at_least = bound.count;
    id.count_at_least_probability = bound.probability;
    if (count_reason.empty()) {
      id.count_identifiable = true;
      id.count = k;
      id.position_probability = cf.configuration_probability[k];
      const double amax = *std::max_element(best.amplitudes.begin(), best.amplitudes.end());
      for (size_t q = 0; q < best.slots.size(); ++q) {
        id.positions_deg.push_back(360.0 * best.slots[q] / z);
        id.relative_strengths.push_back(amax > 0 ? best.amplitudes[q] / amax : 0.0);
      }
    }
  }

  // Width.
  const double c = diagnosis.band.center_hz();
  const double w = std::max(diagnosis.band.width_hz(), options.width_band_min_half_width_hz);
  id.width_band_low_hz = std::max(50.0, c - w);
  id.width_band_high_hz = std::min(0.49 * fs, c + w);
  const std::vector<double> sew =
      SmoothBandSquaredEnvelope(record.samples, fs, id.width_band_low_hz, id.width_band_high_hz);
  WidthFitOptions wo = options.width;
  const double chord_max = 2.0 * std::asin(0.8) / (2.0 * kPi * id.spin_hz);  // w = 0.8 d
  wo.max_delay_s = std::min(
      0.4 / f_b0, options.width_calibration_scale * chord_max + options.width_calibration_offset_s);
  wo.min_delay_s = std::max(wo.min_delay_s, 2.0 / fs);
  wo.noise_correlation_s = 1.0 / (id.width_band_high_hz - id.width_band_low_hz);
  auto finish = [&]() {
    for (const std::string* r : {&count_reason, &width_reason})
      if (!r->empty()) id.reasons.push_back(*r);
    id.reasons.push_back(depth_reason);
    return id;
  };
  if (!id.count_identifiable && !options.width_over_uncertain_count) {
    // Other defective rollers' impacts fall at lags the width fit would take for an entry; only a
    // known configuration (its spin phases) says which lags to leave out.
    width_reason =
        "width: not identifiable (needs the count: other rollers' impacts would pass "
        "for entry events)";
    return finish();
  }
  if (id.count_identifiable && id.count > options.width_max_count) {
    width_reason = "width: not identifiable (" + std::to_string(id.count) +
                   " defective rollers: their impacts pass for each other's entry events; "
                   "stated for at most " +
                   std::to_string(options.width_max_count) + ")";
    return finish();
  }
  if (options.width_contact_release && !options.radial_load_n) {
    width_reason =
        "width: not identifiable (needs the radial load, --load-n: a loaded roller is released "
        "and lands where the spall's gap equals its contacts' elastic approach, which the load "
        "sets)";
    return finish();
  }
  if (!(wo.max_delay_s > wo.min_delay_s)) {
    width_reason = "width: not identifiable (no delay range at this speed and sample rate)";
    return finish();
  }
  if (id.count_identifiable) {
    width_reason = WidthForCount(id.count, sew, fs, z, d, wo, options, &id);
    return finish();
  }
  // The count is not stated: the width is, when every count that holds most of the probability
  // gives the same pair (IdentifyOptions::width_over_uncertain_count).
  std::vector<int> counts;
  double mass = 0.0;
  for (int k = 1; k < static_cast<int>(id.probabilities.size()); ++k)
    if (id.probabilities[k] >= options.width_count_min_probability &&
        k < static_cast<int>(id.count_fit.best.size()) && !id.count_fit.best[k].slots.empty()) {
      counts.push_back(k);
      mass += id.probabilities[k];
    }
  std::sort(counts.begin(), counts.end(), [&](int a, int b) {
    return id.probabilities[a] > id.probabilities[b];
  });
  // The estimate is the most probable count's fit, so that count must be one a stated width may
  // have; a less probable count above width_max_count only adds its own fit to the agreement.
  if (counts.empty() || mass < options.width_count_mass ||
      counts.front() > options.width_max_count) {
    width_reason =
        "width: not identifiable (needs the count: other rollers' impacts would pass "
        "for entry events)";
    return finish();
  }
  // Each candidate count's own fit, least probable first, so that the most probable count's fit
  // is the one left in id; the interval is widened to cover the others'.
  double low = std::numeric_limits<double>::infinity(), high = 0.0;
  std::optional<double> delay;  // the first fit's
  for (auto k = counts.rbegin(); k != counts.rend(); ++k) {
    const std::string why = WidthForCount(*k, sew, fs, z, d, wo, options, &id);
    std::string refused;
    if (!why.empty())
      refused = "the count is not known; with " + std::to_string(*k) +
                " defective rollers: " + (why.rfind("width: ", 0) == 0 ? why.substr(7) : why);
    else if (delay &&
             std::abs(id.width_fit.best.delay_s - *delay) >= options.cross_lag_half_width_s)
      refused = "the count is not known, and " + std::to_string(counts.back()) + " and " +
                std::to_string(*k) + " defective rollers give different entry-exit delays: " +
                FormatNumber("%.2f", *delay * 1e3) + " and " +
                FormatNumber("%.2f", id.width_fit.best.delay_s * 1e3) + " ms";
    if (!refused.empty()) {
      width_reason = "width: not identifiable (" + refused + ")";
      id.width_identifiable = false;
      id.width_m = id.width_low_m = id.width_high_m = 0.0;
      return finish();
    }
    if (!delay) delay = id.width_fit.best.delay_s;
    low = std::min(low, id.width_low_m);
    high = std::max(high, id.width_high_m);
  }
  id.width_low_m = low;
  id.width_high_m = high;
  id.width_counts = counts;
  return finish();
}

std::string Identification::BriefReport() const {
  std::ostringstream os;
  os << "diagnosis: " << dsp::VerdictName(diagnosis.verdict) << " (band "
     << FormatNumber("%.0f", diagnosis.band.low_hz) << "-"
     << FormatNumber("%.0f", diagnosis.band.high_hz) << " Hz)\n";
  // The record's own doubts (clipping, spikes, inseparable races) hold for what follows too.
  for (const std::string& w : diagnosis.warnings)
    os << "WARNING (identification not confident): " << w << "\n";
  if (roller_signature)
    os << "rates: f_c " << FormatNumber("%.4f", cage_hz) << " Hz, f_b "
       << FormatNumber("%.3f", 2.0 * spin_hz) << " Hz (refined), "
       << FormatNumber("%.1f", cage_revolutions) << " cage revolutions\n";
  if (count_identifiable) {
    os << "defective rollers: " << count << " (P = " << FormatNumber("%.3f", probabilities[count])
       << "; cage average " << FormatNumber("%.3f", probabilities_cage[count]);
    if (!probabilities_sidebands.empty())
      os << ", sidebands " << FormatNumber("%.3f", probabilities_sidebands[count]);
    os << ")\n  positions in the cage:";
    for (double p : positions_deg) os << " " << FormatNumber("%.1f", p);
    os << " deg (P = " << FormatNumber("%.2f", position_probability) << ")\n";
  } else {
    os << "defective rollers: not identified\n";
  }
  if (count_at_least > 0)
    os << "  at least " << count_at_least << " defective roller" << (count_at_least == 1 ? "" : "s")
       << " (P(K >= " << count_at_least
       << ") = " << FormatNumber("%.3f", count_at_least_probability) << ")\n";
  if (!probabilities.empty()) {
    os << "  P(K):";
    for (size_t k = 0; k < probabilities.size() && k <= 5; ++k)
      os << " " << k << ":" << FormatNumber("%.3g", probabilities[k]);
    os << "  (fit chi2 scale " << FormatNumber("%.2f", count_fit.chi2_scale) << " / "
       << FormatNumber("%.2f", count_fit.chi2_scale_sidebands) << ")\n";
  }
  if (width_identifiable) {
    os << "width: " << FormatNumber("%.2f", width_m * 1e3) << " mm (90 % interval "
       << FormatNumber("%.2f", width_low_m * 1e3) << "-" << FormatNumber("%.2f", width_high_m * 1e3)
       << " mm; entry-exit delay " << FormatNumber("%.3f", width_fit.best.delay_s * 1e3)
       << " ms)\n";
    if (!width_counts.empty()) {
      os << "  width: the same with each likely count (";
      for (size_t i = 0; i < width_counts.size(); ++i) os << (i ? ", " : "") << width_counts[i];
      os << " defective rollers), although the count itself is not stated\n";
    }
  } else {
    os << "width: not identified\n";
  }
  for (const auto& r : reasons) os << "  " << r << "\n";
  return os.str();
}

std::string Identification::ToJson(int indent) const {
  using nlohmann::ordered_json;
  auto probs = [](const std::vector<double>& p) {
    ordered_json j = ordered_json::object();
    for (size_t k = 0; k < p.size(); ++k) j[std::to_string(k)] = p[k];
    return p.empty() ? ordered_json(nullptr) : j;
  };
  ordered_json j;
  ordered_json dr;
  dr["count"] = count_identifiable ? ordered_json(count) : ordered_json(nullptr);
  dr["probabilities"] = probs(probabilities);
  if (count_at_least > 0)
    dr["at_least"] = {{"count", count_at_least}, {"probability", count_at_least_probability}};
  else
    dr["at_least"] = nullptr;
  dr["probabilities_cage_average"] = probs(probabilities_cage);
  dr["probabilities_sidebands"] = probs(probabilities_sidebands);
  dr["positions_deg"] = count_identifiable ? ordered_json(positions_deg) : ordered_json(nullptr);
  dr["position_probability"] =
      count_identifiable ? ordered_json(position_probability) : ordered_json(nullptr);
  dr["relative_strengths"] =
      count_identifiable ? ordered_json(relative_strengths) : ordered_json(nullptr);
  j["defective_rollers"] = dr;
  if (width_identifiable) {
    ordered_json w;
    w["estimate"] = width_m * 1e3;
    w["interval_90"] = {width_low_m * 1e3, width_high_m * 1e3};
    // Stated without a count: the counts whose configurations all gave this width.
    w["over_counts"] = width_counts.empty() ? ordered_json(nullptr) : ordered_json(width_counts);
    j["width_mm"] = w;
  } else {
    j["width_mm"] = nullptr;
  }
  ordered_json ident;
  ident["width"] = width_identifiable;
  ident["count"] = count_identifiable;
  ident["depth"] = depth_identifiable;
  ident["reasons"] = reasons;
  j["identifiable"] = ident;
  j["diagnosis"] = ordered_json::parse(diagnosis.ToJson(0));
  ordered_json fit;
  fit["roller_signature"] = roller_signature;
  if (roller_signature) {
    fit["cage_hz"] = cage_hz;
    fit["f_b_hz"] = 2.0 * spin_hz;
    fit["surface_speed_m_s"] = surface_speed_m_s;
    fit["cage_revolutions"] = cage_revolutions;
    fit["load_zone_half_angle_deg"] = load_zone_half_angle_rad * 180.0 / kPi;
    fit["load_zone_from_load"] = load_zone_from_load;
    if (!count_fit.best.empty()) {
      const HumpFit& b = count_fit.best[count_fit.MostProbable()];
      fit["hump"] = {{"exponent", b.shape.exponent},
                     {"edge_gain", b.shape.edge_gain},
                     {"smear_deg", b.shape.smear_rad * 180.0 / kPi},
                     {"chi2_cage_average", b.chi2},
                     {"chi2_sidebands", b.chi2_sidebands}};
      fit["cage_bins"] = count_fit.bins;
      fit["sideband_lines"] = count_fit.sideband_lines;
      fit["chi2_scale_cage_average"] = count_fit.chi2_scale;
      fit["chi2_scale_sidebands"] = count_fit.chi2_scale_sidebands;
    }
    fit["width_band_hz"] = {width_band_low_hz, width_band_high_hz};
    if (width_fit.usable) {
      fit["delay_ms"] = {
          {"estimate", width_fit.best.delay_s * 1e3},
          {"interval_90", {width_fit.delay_low_s * 1e3, width_fit.delay_high_s * 1e3}},
          {"standard_error_covariance", width_fit.delay_standard_error_s * 1e3},
          {"second_event_significance", width_fit.delay_power_significance},
          {"power_ratio", width_fit.best.PairPowerRatio()},
          {"rise_ms", width_fit.best.rise_s * 1e3},
          {"delay_rise_ms", width_fit.best.delay_rise_s * 1e3},
          {"from_exclusive_zone", width_from_exclusive_zone},
          {"decay_ms", width_fit.best.decay_s * 1e3},
          {"delay_decay_ms", width_fit.best.PairDecayS() * 1e3}};
      std::vector<double> lags_ms;
      for (double lag : other_rollers_lags_s) lags_ms.push_back(lag * 1e3);
      fit["delay_ms"]["other_rollers_lags"] = lags_ms;
    }
    fit["width_resolution_mm"] = width_resolution_m * 1e3;
    fit["width_calibration"] = {{"contact_release", options.width_contact_release},
                                {"load_fraction", options.width_contact_load_fraction},
                                {"scale", options.width_calibration_scale},
                                {"offset_ms", options.width_calibration_offset_s * 1e3},
                                {"relative_sd", options.width_calibration_relative_sd}};
    if (load_zone_from_load) {
      fit["roller_load_n"] = roller_load_n;
      fit["contact_approach_um"] = contact_approach_m * 1e6;
    }
  }
  j["fit"] = fit;
  // What decided the statements: with these a reader can tell "uncertain" from "not stated here".
  ordered_json settings;
  settings["min_count_probability"] = options.min_count_probability;
  settings["min_count_bound_probability"] = options.min_count_bound_probability;
  settings["width_max_count"] = options.width_max_count;
  settings["width_over_uncertain_count"] = options.width_over_uncertain_count;
  settings["count_needs_cage_hump"] = options.count_needs_cage_hump;
  settings["min_count_hump_exponent"] = options.min_count_hump_exponent;
  settings["flat_hump_max_edge_to_centre"] = options.flat_hump_max_edge_to_centre;
  settings["max_count_hump_exponent"] = options.max_count_hump_exponent;
  settings["combine_per_count"] = options.count.combine_per_count;
  settings["max_count"] =
      options.count.max_count >= 0 ? ordered_json(options.count.max_count) : ordered_json(nullptr);
  settings["radial_load_n"] =
      options.radial_load_n ? ordered_json(*options.radial_load_n) : ordered_json(nullptr);
  settings["sensor_angle_deg"] = options.count.sensor_angle_rad
                                     ? ordered_json(*options.count.sensor_angle_rad * 180.0 / kPi)
                                     : ordered_json(nullptr);
  settings["temperatures"] = {{"cage_average", options.count.temperature_cage},
                              {"sidebands", options.count.temperature_sidebands}};
  settings["sideband_pattern_per_parity"] = options.count.sideband_pattern_per_parity;
  settings["sideband_second_pattern"] = options.count.sideband_second_pattern;
  settings["sideband_spin_step"] = SidebandSpinStep(options);
  settings["width_shared_ring_down"] = options.width.shared_ring_down;
  settings["max_pair_power_ratio"] = std::isfinite(options.max_pair_power_ratio)
                                         ? ordered_json(options.max_pair_power_ratio)
                                         : ordered_json(nullptr);  // null: no upper bound
  j["settings"] = settings;
  return j.dump(indent);
}

}  // namespace spallkit::identify
