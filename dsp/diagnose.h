// The envelope-analysis diagnosis of one record: band selection, squared envelope spectrum, fault
// families, detection with a controlled false-alarm rate, and a verdict.
//
//   record --(optional cepstrum pre-whitening)--> one FFT (EnvelopeAnalyzer)
//          --> fast kurtogram (all nodes of the 1/3-binary tree)
//          --> candidate bands: nodes wide enough to hold every line of at least one race or
//              roller family (and a floor window of SES bins), at most 8x the highest line
//              searched, and starting above half of that highest line (keeps shaft and mains lines
//              of the raw signal out of the demodulation band, where they would beat into SES
//              lines); in a band narrower than the highest line the wider families' top lines are
//              out of range and excluded
//          --> per candidate: SES, robust floor, comb detection of the four families
//          --> chosen band = the candidate with the strongest family evidence (smallest corrected
//              p-value); the kurtogram's best node when no family shows anything
//          --> ranking by p-value; verdict = best detected family, else "healthy".
// The false-alarm budget (DiagnoseOptions::false_alarm_probability, per record) is split by
// Bonferroni over 4 families x all candidate bands x the comb combinations of each family (see
// dsp/detection.h), so a Gaussian-noise record is called faulty with probability <= that budget.
//
// Shaft speed: the comb search is centred on the shaft speed measured from the raw spectrum
// (harmonics 1..5 of f_r within +/- speed_search of the nominal) when it is found, so a nominal
// speed a few percent off does not move the fault lines out of the +/- tolerance window.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/bearing.h"
#include "core/record.h"
#include "dsp/detection.h"
#include "dsp/envelope.h"
#include "dsp/explain.h"
#include "dsp/fault_bands.h"
#include "dsp/kurtogram.h"
#include "dsp/statistics.h"

namespace spallkit::dsp {

// The conclusion of a diagnosis. Strings ("healthy", "outer_race", "inner_race",
// "rolling_element", "cage") only at the JSON/CLI boundary: VerdictName / ParseVerdict.
enum class Verdict { kHealthy, kOuterRace, kInnerRace, kRollingElement, kCage };
inline constexpr int kVerdicts = 5;
const char* VerdictName(Verdict verdict);
// The verdict that names a fault component.
Verdict VerdictOf(FaultComponent component);

// How the reported demodulation band was chosen: the band with the strongest family evidence, or
// (no family significant anywhere) the kurtogram's choice among the candidates. JSON strings
// "fault_evidence" / "kurtogram".
enum class BandSelection { kFaultEvidence, kKurtogram };
const char* BandSelectionName(BandSelection selection);

struct DiagnoseOptions {
  int harmonics = 5;                      // harmonics 1..N of each family
  double tolerance = 0.02;                // +/- slip / speed tolerance of every line (relative)
  double speed_search = 0.05;             // +/- range of the shaft-speed search (relative)
  double false_alarm_probability = 1e-3;  // per record, all families and bands together
  bool prewhiten = false;                 // cepstrum pre-whitening before everything else
  // 0: automatic, one level below the narrowest candidate band (deeper rows hold none).
  int kurtogram_max_level = 0;
  // Also compute the kurtogram two levels deeper than the analysis needs, for its map (the plot
  // of `spall diagnose --plot-dir`); Diagnosis::kurtogram is then that one. The bands, the
  // detections and the verdict do not change. Costs a second kurtogram (~10 ms at 48 kHz, 10 s).
  bool kurtogram_map = false;
  int floor_window_bins = 401;  // running-median window of the SES floor
  // A family is claimed (detected) only if the record holds this many periods of its
  // fundamental; otherwise its reason says "not claimed" (the cage on short records).
  double min_periods = 20.0;
  double line_p_value = 1e-3;    // "individually significant" line
  double min_modulation = 0.12;  // ...and modulating >= this fraction of mean(SE)
  // Search the first_bands candidates of highest spectral kurtosis first, and the others only
  // when none of those shows a detected family (0: all in one go). The Bonferroni factor counts
  // every candidate either way, so the false-alarm design does not change; a faulty record
  // usually stops after the first stage (each band costs an SES, a floor and four combs).
  int first_bands = 16;
  // An outer-race verdict must survive cepstrum pre-whitening: its comb (any candidate band)
  // must stay significant on the pre-whitened record, else the family is not claimed. Every
  // healthy rolling bearing is modulated at Z f_c = BPFO by the rollers passing the load zone
  // (varying compliance); that response is deterministic, discrete raw lines at n Z f_c, which
  // pre-whitening flattens, whereas a spall's impacts (with their slip jitter) survive it. Costs
  // a second analysis on records called outer_race. Off when `prewhiten` is already set.
  bool confirm_outer_race = true;
  // ...and the band where its comb survives pre-whitening must start at or above this many times
  // the outer race's fundamental (kinematic BPFO). Varying compliance is a smooth load change per
  // roller passage: its discrete raw lines sit at low orders of Z f_c (up to order 13 in the
  // simulated healthy N205EM), and a narrow band among them turns their beats into a BPFO comb
  // that pre-whitening keeps. A spall's impacts ring the structure far above those orders (the
  // measured outer-race records confirm up to order 40). When no candidate band starts that high
  // below fs/2, any band confirms and the Diagnosis warns that the record cannot tell the two
  // apart. 0: any band confirms.
  double outer_race_min_band_orders = 20.0;
  // Candidate bands start at or above this frequency (Hz) besides the automatic lower limit
  // (half the highest line searched); 0: the automatic limit only. Keeps a known low-frequency
  // source (gear mesh, a structural resonance) out of the band search.
  double min_band_low_hz = 0.0;
  // Threads (OpenMP) for the candidate bands and the kurtogram's two chains; 0: automatic,
  // min(number of processors, 4). Each band is computed by one thread with its own buffers and
  // the bands are compared in the same fixed order as with one thread, so the Diagnosis is
  // bit-identical for every thread count; only the wall time changes.
  int threads = 0;
  static constexpr int kMaxThreads = 64;
  static constexpr int kMaxHarmonics = 20;
  static constexpr double kMaxTolerance = 0.1;  // 10 %

  bool IsValid(std::string* error) const;
};

// Everything the diagnosis found, in SI units (Hz). BriefReport() and ToJson() render it.
struct Diagnosis {
  Verdict verdict = Verdict::kHealthy;  // the first detected family, else healthy
  std::vector<FamilyDetection> faults;  // all four families, most significant first
  // Why the verdict should not be trusted (clipping, spikes: dsp/record_check.h); empty when the
  // record looks sound. Records that cannot be analysed at all are refused (InputError).
  std::vector<std::string> warnings;
  std::vector<FaultFamily> families;  // kinematic lines searched (same order as kFaultComponents)

  Band band;                   // demodulation band used for the reported SES
  double band_kurtosis = 0.0;  // spectral kurtosis of that node
  double band_level = 0.0;     // kurtogram level of that node
  BandSelection band_selection = BandSelection::kKurtogram;
  KurtogramNode kurtogram_best;
  int candidate_bands = 0;    // nodes that met the width/position rule (the Bonferroni count)
  int searched_bands = 0;     // of those, searched before a detection stopped the search
  double multiplicity = 0.0;  // families x candidate bands (Bonferroni factor on top of combs)

  BearingFrequencies kinematics;  // at the nominal speed
  std::string bearing;
  std::optional<double> measured_shaft_hz;
  std::optional<double> measured_f_b_hz, measured_f_c_hz;
  std::optional<double> f_b_slip_percent, f_c_slip_percent;  // measured / kinematic - 1, in %
  // What measured f_c: CageRateMeasurement::Source() of a roller spall (dsp/explain.h), or
  // "cage comb"; empty when f_c was not measured.
  std::string f_c_source;

  // Lines claimed by the detected families (joint explanation, dsp/explain.h), claiming order.
  std::vector<ExplainedLine> explained_lines;
  // Rolling-element comb: f_b / f_sb relative distance to the nearest integer (NaN: not tested).
  double roller_integer_ratio_mismatch = 0.0;
  // Rolling element against cage comb (dsp/explain.h); when both were detected and the record
  // cannot resolve them, warnings[] says so.
  RollerCageSeparation roller_cage;
  // Outer against inner race on the harmonics only one of them predicts (dsp/explain.h); when
  // both were detected and cannot be told apart, warnings[] says so.
  RaceSeparation races;

  TimeStatistics statistics;  // of the record as given (before pre-whitening)
  double sample_rate_hz = 0.0;
  int samples = 0;
  std::string source, channel, units;
  DiagnoseOptions options;

  EnvelopeSpectrum ses;           // SES of the chosen band (level = |FFT(SE - mean)|/N)
  NormalizedSpectrum normalized;  // SES power over its floor, same bins
  Kurtogram kurtogram;

  // The family ranked first (nullptr if none).
  const FamilyDetection* Best() const { return faults.empty() ? nullptr : &faults.front(); }
  // A few readable lines: verdict, band, ranked families with their evidence, measured rates.
  std::string BriefReport() const;
  // One JSON object; keys documented in docs/DIAGNOSIS.md (stable).
  std::string ToJson(int indent = 2) const;
};

// Throws InputError for a non-positive shaft speed or sample rate, fault frequencies above
// Nyquist, a record too short for the analysis, a constant record or a non-finite sample
// (dsp/record_check.h), or invalid options. Spikes and clipping give Diagnosis::warnings.
Diagnosis Diagnose(const Record& record,
                   const BearingGeometry& bearing,
                   double shaft_hz,
                   const DiagnoseOptions& options = {});

// Speed estimate from the raw spectrum: shaft harmonics 1..5 searched as a comb within
// +/- search of nominal_hz. Returns the measured shaft frequency when the comb is significant
// (p <= 1e-3 and >= 2 harmonics) and its 1x or 2x line is among the significant ones, else
// nullopt.
std::optional<double> EstimateShaftSpeed(const EnvelopeAnalyzer& analyzer,
                                         double nominal_hz,
                                         double search);

}  // namespace spallkit::dsp
