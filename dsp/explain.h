// Joint explanation of the SES lines: which fault family accounts for which line.
//
// Why: the four families are not independent hypotheses. Their lines share a lattice of shaft and
// cage combination frequencies, so one strong fault feeds the other combs:
//   - a roller spall strikes at f_b, is load-zone modulated once per cage turn (lines k f_b +/- m
//     f_c AND the modulation itself, m f_c), and its alternating outer/inner hits add 1 x BSF =
//     f_b / 2; for an N205EM f_b - f_c = 12.85 f_c lies within 1 % of BPFO = 13 f_c, and the
//     whole roller "forest" j BSF +/- m f_c lies within ~1 % of integer multiples of f_c (BSF =
//     6.92 f_c), so both the outer-race and the cage combs light up;
//   - BPFO = Z f_c exactly, so an outer-race comb is a sub-comb of a cage comb.
// Testing each family alone (or letting one "exclude" another's harmonics within the +/- slip
// tolerance) calls the cage or the outer race on a textbook roller spall. Instead: rank the
// detected families, let the first one claim the lines it explains at their MEASURED sub-bin
// positions (a window of a few bins, not the slip tolerance), re-test the others on what is left
// with the same false-alarm control, and repeat.
//
// Ranking. A detected rolling-element comb (f_b harmonics with f_c sidebands) explains the cage
// lines, unless its rate is an integer multiple of its own sideband spacing (f_b / f_sb within
// integer_ratio_tolerance of an integer): then the "roller forest" is just a dense cage comb
// (f_b / f_c = 2 (1 + d_m / d) is never an integer for the catalogue bearings: 13.85 N205EM, 11.83
// 6205, 10.45 6203) and the cage explains it, provided the cage's harmonic evidence is also the
// stronger: a cage comb is an f_c impulse train whose lines decay with order, so its own low
// harmonics outweigh the lines at f_b, while a roller spall's f_b line is its strongest. (A
// roller spall whose cage slips more than its rollers, 1.8 % against 1.1 % on the simulated
// three-roller spalls, puts the measured ratio within 0.5 % of 14 on an N205EM even where the
// record resolves the two; on the ratio alone its strongest line was explained away.) On a
// record too short to resolve the bearing's f_b from the nearest cage harmonic the ratio is
// not even measured well (RollerCageSeparation). Other pairs are ordered by harmonic evidence
// (mean -ln p of the family's own harmonics, dsp/detection.h), which the lattice coincidences
// feed least.
#pragma once

#include <string>
#include <vector>

#include "core/bearing.h"
#include "dsp/detection.h"
#include "dsp/fault_bands.h"

namespace spallkit::dsp {

struct ExplanationOptions {
  // A predicted line takes the strongest SES bin within this many bins of its position...
  double match_bins = 1.5;
  // ...and claims the lines of other families within this many bins of that peak (+ the
  // detection's guard fraction of the frequency for the slip smear of high harmonics).
  double window_bins = 3.0;
  // Sideband orders claimed around harmonics: +/- m f_c (rolling element, outer race), +/- m f_r
  // (inner race), m = 1..sideband_orders.
  int sideband_orders = 2;
  // |f_b / (n f_sb) - 1| below this (n the nearest integer): the roller comb is a cage comb.
  double integer_ratio_tolerance = 0.005;
  // The integer-ratio test is asked only when the record resolves the bearing's f_b from the
  // nearest cage harmonic n f_c by at least this many SES bins (RollerCageSeparation).
  double roller_cage_resolution_bins = 2.0;

  bool IsValid(std::string* error) const;
};

// Rates at which a detected family's lines are predicted.
struct FamilyRates {
  double fundamental_hz = 0.0;  // measured f0 (FamilyDetection::fundamental_hz)
  double sideband_hz = 0.0;     // measured sideband spacing, else kinematic x speed scale
  bool sideband_measured = false;
};

// The family's measured fundamental, and its sideband spacing: for the rolling element f_c from
// the +/- f_c pairs (mean half-distance of the significant pairs; sideband_measured = false when
// no harmonic has both; then single significant sidebands against k f_b), for the inner race the
// shaft speed `shaft_hz`, for the outer race `cage_hz` (kinematic) x the comb's speed scale.
FamilyRates MeasureRates(const FamilyDetection& detection,
                         const FaultFamily& family,
                         double cage_hz,
                         double shaft_hz);

// The rate at which a detected roller spall goes round, f_c, for the report. The spall is
// load-zone modulated once per cage turn, so its SES carries f_c twice: as the spacing of the
// +/- m f_c sidebands around k f_b and as the modulation lines m f_c themselves (f_c from the
// FTF line or from the sideband spacing). Least squares over both, each estimate weighted
// by the inverse of its error in units of one peak's error: a sideband pair's half-distance
// (hi - lo) / 2 with weight 2, a modulation line f_m / m with weight m^2. Single sidebands
// against the measured k f_b (error of two peaks and of k f_b) only when neither is present.
// Modulation lines count when they are a significant local peak (ExplanationOptions::match_bins
// around m times the running estimate, walking upward), lie below the roller forest (m f_c <
// f_b / 2 - (sideband_orders + 1/2) f_c) and are resolved from the shaft orders (multiples of
// shaft_hz / DetectionOptions::shaft_order_divisor) and the mains harmonics: more than one bin
// away. (The detection excludes a wider guard around those; the measurement only needs the
// peak to be its own.) hz = 0 when nothing measured it.
struct CageRateMeasurement {
  double hz = 0.0;
  int sideband_pairs = 0;
  int modulation_lines = 0;
  int single_sidebands = 0;    // used only when the two above are 0
  std::string Source() const;  // e.g. "2 sideband pairs + 1 modulation line"
};
CageRateMeasurement MeasureRollerCageRate(const NormalizedSpectrum& spectrum,
                                          const FamilyDetection& roller,
                                          const FaultFamily& family,
                                          double cage_hz,
                                          double shaft_hz,
                                          const DetectionOptions& options,
                                          const ExplanationOptions& explanation = {});

// Every line a fault of this family puts in the SES below max_hz, at the given rates:
//   outer race      k BPFO, k BPFO +/- m f_c
//   inner race      k BPFI, k BPFI +/- m f_r
//   rolling element k f_b and (k - 1/2) f_b (1 x BSF series), each +/- m f_c; m f_c (modulation)
//   cage            k f_c for every k (a cage fault is an impulse train at f_c)
// Harmonics k = 1..harmonics (cage: all up to max_hz); m = 1..sideband_orders.
std::vector<double> PredictedLines(FaultComponent component,
                                   const FamilyRates& rates,
                                   int harmonics,
                                   int sideband_orders,
                                   double max_hz);

// The significant SES peaks (pair p-value <= options.line_p_value) at predicted lines, each with
// its claim window. Harmonic series are followed upward with the rate re-estimated from the peaks
// found so far, so a slightly wrong rate does not walk off the lines at high orders.
std::vector<ExplainedLine> ClaimLines(const NormalizedSpectrum& spectrum,
                                      const std::vector<double>& predicted_hz,
                                      FaultComponent by,
                                      const DetectionOptions& options,
                                      const ExplanationOptions& explanation = {});

// Outer race against inner race on lines that only one of them predicts. For a 6205, 3 BPFO
// lies 0.7 % from 2 BPFI and 6 BPFO from 4 BPFI (MFPT bearing: 3 BPFO 2.4 % from 2 BPFI), so a
// strong race fault feeds the other race's comb with coincident harmonics, and the inner race's
// +/- f_r sidebands around such a harmonic are then only the shaft modulation of the other
// fault's line. A harmonic is shared when it lies within the claim window (window_bins bins +
// the guard fraction of its frequency) of any multiple of the other family's measured
// fundamental.
struct RaceSeparation {
  bool tested = false;  // both races detected on their own
  // Mean uncapped -ln p of the non-excluded harmonics that are not shared (0: none), and how
  // many of them are significant.
  double outer_evidence = 0.0, inner_evidence = 0.0;
  int outer_significant = 0, inner_significant = 0;
  // Neither race has a significant harmonic of its own: the record cannot tell them apart at
  // its resolution; the order then falls back on the harmonic evidence of all lines.
  bool separable = true;
  std::string Describe() const;  // one line for a warning
};
RaceSeparation SeparateRaces(const FamilyDetection& outer,
                             const FamilyDetection& inner,
                             double resolution_hz,
                             const DetectionOptions& options,
                             const ExplanationOptions& explanation = {});

// Rolling element against cage comb. A cage comb (an impulse train at f_c) holds a "roller comb"
// at n f_c with +/- f_c "sidebands", n the integer nearest the bearing's f_b / f_c, so the two
// are told apart by how far the measured f_b lies from n times the measured cage rate (the
// integer-ratio test, ExplanationOptions::integer_ratio_tolerance). That needs the record to
// resolve the bearing's own offset |f_b - n f_c| (N205EM: 0.15 f_c, 1.25 Hz at 1200 rpm; 6205:
// 0.17 f_c): below roller_cage_resolution_bins SES bins the roller forest's lines around the low
// cage orders (BSF +/- m f_c, 0.08 f_c from 7 f_c on an N205EM) pull the measured cage rate by
// up to a bin (a simulated roller spall on a 1 s record: 0.7-0.9 % low, the ratio lands on 14),
// and the test decides on its own measurement error; nor can the harmonic evidence decide alone
// (a roller spall's load-zone lines m f_c can outweigh its f_b harmonics). The roller comb is
// taken for a cage comb only when the ratio sits on the integer AND the cage's harmonic
// evidence is the stronger (on every record), and where the two are not separable the report
// says so.
struct RollerCageSeparation {
  bool tested = false;           // both the rolling element and the cage were detected on their own
  double offset_hz = 0.0;        // |f_b - n f_c| at the searched speed (kinematic ratio)
  double offset_bins = 0.0;      // offset_hz over the SES resolution 1 / T
  bool separable = true;         // offset_bins >= roller_cage_resolution_bins
  std::string Describe() const;  // one line for a warning
};

struct JointExplanation {
  // Detected families in explanation order, then the others by p-value.
  std::vector<FamilyDetection> ranked;
  std::vector<ExplainedLine> explained;  // every claimed line, in claiming order
  // f_b / f_sb - nearest integer, relative; NaN when not tested (no measured sideband spacing).
  double roller_integer_ratio_mismatch = 0.0;
  bool roller_is_cage_comb = false;
  RollerCageSeparation roller_cage;
  RaceSeparation races;  // tested when both races were detected on their own
};

// `detections` are the four families tested independently on `spectrum` with `context`, in the
// order of `families`. Re-tests use the same context (multiplicity, shaft and mains exclusions)
// plus the claimed lines.
JointExplanation ExplainJointly(const NormalizedSpectrum& spectrum,
                                const std::vector<FaultFamily>& families,
                                std::vector<FamilyDetection> detections,
                                const DetectionContext& context,
                                const DetectionOptions& options,
                                const ExplanationOptions& explanation = {});

}  // namespace spallkit::dsp
