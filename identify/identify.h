// Identification of a roller spall from a vibration record: how many rollers are defective, where
// they sit in the cage, and how wide the spall is, each with its uncertainty, or the reason the
// record cannot say (docs/IDENTIFY.md).
//
//   Record + Diagnosis (dsp/diagnose.h: verdict, band, measured f_b and f_c)
//     -> refusals: no roller signature (verdict not rolling_element) / a race fault
//     -> squared envelope in the diagnosis band; f_c and f_s = f_b / 2 refined to a fraction of a
//        bin (identify/line_dft.h)
//     -> count and positions: cage-synchronous average + f_c sideband pattern, K = 0..Z with Ceres,
//        P(K) from the evidence (identify/count_fit.h)
//     -> width: load-zone autocorrelation of a smooth wide-band squared envelope, entry-exit delay
//        dt with a bootstrap interval (identify/width_fit.h), w = d sin(pi f_s dt + 2 sqrt(delta /
//        d)): the roller is released and lands where the spall's gap equals the contacts' elastic
//        approach delta (IdentifyOptions::width_contact_release)
//     -> depth: never (the response does not depend on it; docs/IDENTIFY.md).
// A library user does what `spall identify` does in a few lines:
//     Record r = ReadRecord(path, {});
//     BearingGeometry g = CatalogBearing("N205EM");
//     dsp::Diagnosis d = dsp::Diagnose(r, g, rpm / 60.0);
//     identify::IdentifyOptions o;  o.radial_load_n = 10000.0;
//     identify::Identification id = identify::Identify(r, g, rpm / 60.0, d, o);
//     std::cout << id.BriefReport();   // or id.ToJson()
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/bearing.h"
#include "core/record.h"
#include "dsp/diagnose.h"
#include "identify/cage_average.h"
#include "identify/count_fit.h"
#include "identify/spin_sidebands.h"
#include "identify/width_fit.h"

namespace spallkit::identify {

struct IdentifyOptions {
  // Radial load (N): fixes the load zone's half angle (Harris-Jones). Unset: fitted.
  std::optional<double> radial_load_n;
  double diametral_clearance_m = 20e-6;  // for the load zone (N205EM's default; docs/SCENE.md)
  double roller_length_m = 0.0;          // for the load zone; 0: 1.4 x element diameter
  int cage_bins = 72;
  int min_cage_revolutions = 4;
  int sideband_harmonics = 4;  // spin harmonics j of feature B
  int sideband_orders = 4;     // f_c orders m of feature B
  // Feature B's lines are the harmonics of sideband_spin_step x f_s. 2: those of f_b = 2 f_s, on
  // which a roller's outer- and inner-race impacts (half a spin turn apart) add, so that their
  // cage-angle pattern is the cage average's (feature A's hump); 1: every spin harmonic, whose odd
  // ones carry the difference of the two impacts with another pattern, which one shared pattern
  // fits only with a phantom roller (docs/IDENTIFY.md, "Count and positions"). With
  // CountFitOptions::sideband_pattern_per_parity the step is 1 (that model is about the parity).
  int sideband_spin_step = 2;
  CountFitOptions count;
  // The count is reported when its probability reaches this; otherwise it is "uncertain". 0.6:
  // on the tuning sets (docs/IDENTIFY.md) the counts stated at P 0.5-0.6 were right 8 times of
  // 20, those at 0.6-0.65 11 of 12.
  double min_count_probability = 0.6;
  // A lower bound on the count, "at least k defective rollers", is stated at the largest k >= 1
  // whose tail probability P(K >= k) reaches this, wherever the count fit passes every rule but
  // the count's own probability (a stated count, or an uncertain one): rollers in adjacent or
  // near slots merge their humps, so the fit often splits between k and k + 1 while ruling out
  // fewer than k. 0.9 was set before it was measured (docs/IDENTIFY.md, "Lower bound").
  double min_count_bound_probability = 0.9;
  // A count is stated only where the cage-synchronous average (feature A) by itself ranks a
  // count of one or more first: the load-zone humps are the count's physical evidence, and the
  // f_c sideband pattern alone (feature B) ranks a phantom second roller first on many one-roller
  // records (docs/IDENTIFY.md, "Count and positions"). On the six lumped validation
  // sets no count is stated where feature A ranks 0 first; on the hybrid records of the paper's
  // width experiment, with feature B on every spin harmonic, all 8 such statements were wrong
  // (0.46 mm spalls stated as 2 or 3 at P 0.62-0.95; docs/IDENTIFY.md, "Hybrid records of the
  // paper's experiment"). false: the combined probability alone decides.
  bool count_needs_cage_hump = true;
  // A count is not stated when its load-zone hump (feature A's fit of the most probable count) has
  // a shape at the edge of what the fit allows, which no single roller's strikes give:
  // - as flat as it can be: exponent p below min_count_hump_exponent (the fit's lower bound is
  //   0.25) and no edge peaks (HumpShape::EdgeToCentre() below flat_hump_max_edge_to_centre).
  //   Such a flat-topped hump is wider than one roller's load zone makes it, and that is how
  //   adjacent defective rollers show: their humps, one cage slot (27.7 deg on the N205EM)
  //   apart, merge into one that a smaller count with its flattest shape fits as well. Every
  //   count it refuses on the six lumped validation sets was wrong, each on rollers in adjacent
  //   slots (2 for 3 and 1 for 2; their edge-to-centre ratios 1.0-1.3). 0.3 was chosen on the
  //   tuning-side sets (0 right and 7 wrong counts refused; 0.26: 0 and 3; 0.35: 2 and 11) and
  //   checked on the report sets (0 right, 7 wrong). The edge condition was added for the hybrid
  //   model, whose one-roller humps reach the lowest exponent with edges 4-11 times their
  //   centre (strikes hardest where the roller enters and leaves the load zone); without it 6 of
  //   its right counts are refused.
  // - as narrow as it can be: p above max_count_hump_exponent (the upper bound is 6), humps
  //   that cover the middle third of the load zone while a spall strikes all across it: the
  //   configuration splits strikes between humps (one roller's entry and exit lobes read as two
  //   rollers on the hybrid model) rather than following rollers. 5.0 is the lower rule's
  //   margin mirrored (a factor 1.2 inside the bound); no count on the tuning side reaches it;
  //   on the report sets it refuses 3 wrong counts, on the hybrid records of the paper's
  //   experiments 4, and no right one.
  // docs/IDENTIFY.md, "Count and positions". min_count_hump_exponent 0 and
  // max_count_hump_exponent 6: no such rules.
  double min_count_hump_exponent = 0.3;
  double flat_hump_max_edge_to_centre = 2.0;
  double max_count_hump_exponent = 5.0;
  WidthFitOptions width;
  // Width band: Hann window centred on the diagnosis band, +/- max(its width, this) (Hz).
  double width_band_min_half_width_hz = 2000.0;
  // From the measured delay to the width. A loaded roller does not lose contact at the spall's
  // edge: its contacts are compressed by their elastic approach delta(Q) (inner plus outer race,
  // Palmgren's line contact at the passage's load Q), so the spall's gap under the race must first
  // grow past delta, which takes sqrt(d delta) of rolling; it is seated again sqrt(d delta) before
  // the trailing edge. The two events (release, seating) are dt = (arc - 2 sqrt(d delta)) / v
  // apart, v the roller's surface speed. width_contact_release takes that into account (needs
  // the radial load). Q = width_contact_load_fraction x the load-line roller load (Harris-Jones):
  // 0.7, the fraction (grid 0.5-1 by 0.1) whose widths have the smallest mean error on the
  // calibration set (datasets/sweeps/identify-width.toml, clean, 10 and 0 dB: -1.1 %), about the
  // load at +/- 40 deg where the simulated impacts are strongest (docs/IDENTIFY.md, "Width").
  // Records of the synthetic signal model (identify/synthetic_record.h) place their two events
  // at the spall's edges: no release term there.
  bool width_contact_release = true;
  double width_contact_load_fraction = 0.7;
  // A remaining linear calibration of the delay, dt = scale dt_model + offset, and the relation's
  // relative scatter in width (one standard deviation between records), which widens the 90 %
  // interval: 0.065, the standard deviation of the calibration set's width errors (19 widths
  // stated at the three SNRs with one ring-down for both correlation peaks: 6.4 %; 28 with the
  // default's own pair ring-down: 5.3 %, the wider value kept).
  double width_calibration_scale = 1.0;
  double width_calibration_offset_s = 0.0;
  double width_calibration_relative_sd = 0.065;
  // The width is stated only with at most this many defective rollers: the sets hold up to
  // three. Chosen on the tuning-side sets (datasets/sweeps/identify-tune.toml,
  // identify-width.toml, identify-width-multi.toml, identify-width-three.toml; clean, 10 and
  // 0 dB, everything stated): with cross_lag_half_width_s, widths of records counted as two and
  // three rollers are within 15 % as often as those counted as one (14 of 15 and 9 of 9, against
  // 24 of 30; docs/IDENTIFY.md, "Width").
  int width_max_count = 3;
  // Without a stated count: the width is still stated when the likely counts (K >= 1 with
  // P(K) >= width_count_min_probability) together hold at least width_count_mass of the
  // probability, the most probable of them is at most width_max_count, and the width fit of each
  // one's best configuration states the same pair (delays within cross_lag_half_width_s); the
  // estimate is the most probable count's, the interval covers all of theirs. The width fit
  // needs a configuration only to know which lags are other rollers' impacts; when every likely
  // configuration leads to the same pair, that pair does not depend on the count, and a likely
  // count above width_max_count only adds one more fit that must agree. The two numbers were set
  // before any measurement (a count below 0.05 is not a likely one; 0.9 leaves as little
  // unexamined as the 90 % interval does). Checked on the tuning-side sets (clean, 10 and 0 dB):
  // 16 more widths stated, all within 15 %; on the report sets 13 more, one wrong
  // (docs/IDENTIFY.md, "Width without a stated count"). false: a width needs a stated count.
  bool width_over_uncertain_count = true;
  double width_count_min_probability = 0.05;
  double width_count_mass = 0.9;
  // Width reported when the second event's power is this many bootstrap standard deviations
  // above zero and the 90 % interval's half width is at most this fraction of the estimate.
  double min_delay_significance = 2.0;
  // The release drops the roller's whole load and the landing restores it: two events of about
  // the same strength, A ~ B. Two events correlate at their delay with AB <= (A^2 + B^2) / 2, half
  // the zero-lag power (noise included). A "second event" below min_pair_power_ratio of the
  // zero-lag power (B < A / 10) is not that pair (on the simulator's narrow spalls, which are
  // never released: a beat of two housing modes). No upper bound by default:
  // the ratio's denominator adds the noise peak's height to the events' zero-lag area, and where
  // the noise's correlation time is as long as an event's rise the fit moves part of the
  // zero-lag peak into it, so a true pair can read above 1 (48 of the tuning side's 131 widths,
  // up to 4.6, all within 15 %); max_pair_power_ratio 1, measured and not kept, states 51 fewer
  // widths within 15 % there and no fewer wrong ones (docs/IDENTIFY.md, "Width").
  // SignalModelOptions(): no lower bound (its entry is a weak unloading).
  double min_pair_power_ratio = 0.1;
  double max_pair_power_ratio = std::numeric_limits<double>::infinity();
  double max_width_relative_half_interval = 0.3;
  // With several defective rollers, one roller's impacts correlate with another's at the lag of
  // their spin phases (feature B's fit). A delay within this of such a lag may be that
  // correlation rather than a release and landing, and no width is stated. The window is the
  // predicted lags' error: on the signal model's two-roller records (spin phases random-walking
  // between cage revolutions) the correlation peak lay up to 0.22 ms from the predicted lag. On
  // the tuning-side sets, without the rule, all but one of the misread two-roller widths (narrow
  // spalls that are never released, read 1.7-2.4 mm) lay within 0.1 ms of a predicted lag
  // (docs/IDENTIFY.md, "Width").
  double cross_lag_half_width_s = 0.25e-3;
  // A delay within cross_lag_half_width_s of another roller's lag is still stated when the
  // autocorrelation taken only where one defective roller has the load zone to itself shows the
  // same pair: its delay within cross_lag_half_width_s of the whole zone's, significance >=
  // min_delay_significance and power ratio >= width_exclusive_min_pair_power_ratio (then the
  // gates below apply to that fit). "To itself": its fitted hump (feature A) above 0.3 of its own
  // peak and the other defective rollers' humps together below width_exclusive_ratio of it, at
  // the sample and at the longest lag after it. By the fitted humps another roller's impacts are
  // there at most that fraction of the roller's own, so their correlation stays below the
  // min_pair_power_ratio a release and landing must show (the two defaults are the same number
  // for that reason; unmodelled impacts outside the load zone are why the refit must also find
  // the pair strong). 0: the lag rule refuses every such delay (docs/IDENTIFY.md, "Width").
  double width_exclusive_ratio = 0.1;
  // The refit's pair must correlate at least at this fraction of the zero-lag power: 0.2, the
  // low end of the 0.23-0.82 measured on the calibration records whose width is right
  // (min_pair_power_ratio above); SignalModelOptions(): 0, as there.
  double width_exclusive_min_pair_power_ratio = 0.2;
  // The widest spall the calibration covers, as a fraction of the element diameter: a fit beyond
  // it extrapolates the calibration (or has locked onto another event) and is not stated. Default:
  // the widest of the calibration set (2.5 mm on the N205EM's 6.5 mm roller,
  // datasets/sweeps/identify-width.toml); SignalModelOptions(): the fit's own range (0.8).
  double width_max_diameter_fraction = 2.5 / 6.5;

  bool IsValid(std::string* error) const;
};

// The options calibrated for records of the synthetic signal model (identify/synthetic_record.h)
// instead of spallkit's simulator: untempered evidence (the model is exact there), humps down to
// 0.1 of the strongest counted (no unmodelled impacts outside the load zone), the geometric
// width relation (events at the spall's edges, no scatter), and feature B on every spin harmonic
// (sideband_spin_step 1: there the outer- and inner-race events share one cage-angle pattern, so
// the odd harmonics fit the one-pattern model too and add their lines), and the width fit's pair
// peak with the zero-lag peak's ring-down (WidthFitOptions::shared_ring_down: both events ring
// the same resonances there).
IdentifyOptions SignalModelOptions();

struct Identification {
  // What the record supports; the reasons say why not, one line each.
  bool roller_signature = false;
  bool count_identifiable = false;
  bool width_identifiable = false;
  bool depth_identifiable = false;
  std::vector<std::string> reasons;

  // Count and positions (when count_identifiable).
  int count = 0;
  std::vector<double> probabilities;  // P(K), K = 0..max_count (empty: not computed)
  // At least this many defective rollers, with P(K >= count_at_least); 0: no bound stated
  // (IdentifyOptions::min_count_bound_probability).
  int count_at_least = 0;
  double count_at_least_probability = 0.0;
  std::vector<double> probabilities_cage;       // feature A alone
  std::vector<double> probabilities_sidebands;  // feature B alone (empty when not used)
  std::vector<double> positions_deg;       // defective rollers in the cage, from the first, in the
                                           // direction of rotation (canonical: smallest arc)
  std::vector<double> relative_strengths;  // their hump heights / the largest
  double position_probability = 0.0;       // of these slots among the configurations of `count`

  // Width (when width_identifiable).
  double width_m = 0.0, width_low_m = 0.0, width_high_m = 0.0;  // estimate and 90 % interval
  double width_resolution_m = 0.0;  // the narrowest width the record resolves

  // What the fits used.
  double cage_hz = 0.0, spin_hz = 0.0;  // refined f_c and f_s (f_b = 2 f_s)
  double surface_speed_m_s = 0.0;       // pi d f_s
  double cage_revolutions = 0.0;
  double load_zone_half_angle_rad = 0.0;
  bool load_zone_from_load = false;
  double roller_load_n = 0.0;       // the load-line roller load (with the radial load)
  double contact_approach_m = 0.0;  // inner plus outer race approach at the passages' load
  double width_band_low_hz = 0.0, width_band_high_hz = 0.0;
  CageAverage cage_average;
  SpinSidebands sidebands;
  CountFit count_fit;
  WidthFit width_fit;
  // The width's fit where each defective roller has the load zone to itself, made when the delay
  // of width_fit lies on another roller's lag; it replaces width_fit when it confirms the delay.
  WidthFit width_fit_exclusive;
  bool width_from_exclusive_zone = false;
  // The counts the width was stated for when the count itself is not
  // (IdentifyOptions::width_over_uncertain_count); empty otherwise.
  std::vector<int> width_counts;
  // Lags at which the other defective rollers' impacts correlate with one roller's (from the
  // spin phases; empty for one roller): a delay on one of them is not stated.
  std::vector<double> other_rollers_lags_s;
  dsp::Diagnosis diagnosis;
  IdentifyOptions options;

  // A short report: count with its probability, width with its interval, positions, fit
  // quality, what could not be identified and why.
  std::string BriefReport() const;
  // One JSON object; keys documented in docs/IDENTIFY.md.
  std::string ToJson(int indent = 2) const;
};

// Identifies from a diagnosis of the same record. Throws InputError for invalid options or a
// record/diagnosis mismatch (sample rate, length).
Identification Identify(const Record& record,
                        const BearingGeometry& bearing,
                        double shaft_hz,
                        const dsp::Diagnosis& diagnosis,
                        const IdentifyOptions& options = {});

// The width relation (docs/IDENTIFY.md, "Width"): the spall width of a release-landing delay
// on a roller of diameter d, at the identification's spin rate and contact approach, and its
// inverse (0 for a width too narrow to release the roller).
double WidthOfDelay(double delay_s, double d, const Identification& id, const IdentifyOptions& o);
double DelayOfWidth(double width_m, double d, const Identification& id, const IdentifyOptions& o);

// Why a count fit's most probable count is not stated ("count: ..."), or empty when it is: no
// hump at all, none from the cage average by itself (count_needs_cage_hump), a probability below
// min_count_probability, a hump as flat or as narrow as its shape allows (min_count_hump_exponent,
// max_count_hump_exponent), or the two features confidently naming different counts.
std::string CountRefusal(const CountFit& fit, const IdentifyOptions& options);

// "At least `count` defective rollers" with P(K >= count) = probability: the largest count >= 1
// whose tail reaches min_count_bound_probability, where the fit passes every statement rule of
// CountRefusal but the count's own probability; count 0 when no bound is stated.
struct CountBound {
  int count = 0;
  double probability = 0.0;
};
CountBound LowerCountBound(const CountFit& fit, const IdentifyOptions& options);

}  // namespace spallkit::identify
