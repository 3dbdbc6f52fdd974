// Fault families and fault-band metrics for envelope-spectrum diagnosis.
//
// A bearing fault shows in the squared envelope spectrum (SES) as a FAMILY of lines, not one line:
//
//   component        lines                    sidebands (why)
//   outer_race       k * BPFO                 none (the fault is fixed in the load zone)
//   inner_race       k * BPFI                 k * BPFI +/- f_r (the fault turns through the load
//   zone
//                                             once per shaft turn, amplitude-modulating the
//                                             impacts)
//   rolling_element  k * f_b                  k * f_b +/- f_c (the roller goes round with the cage)
//   cage             k * f_c                  none
//
// f_b is the ROLLING-ELEMENT DEFECT RATE = 2 x roller spin (BSF), spallkit's convention: a spall on
// a roller strikes both races once per roller revolution (CWRU's ball factor 4.7135 = 2 x 2.357).
// MATLAB's bearingFaultBands calls 1 x spin "Fb"; searching only there misses roller faults.
//
// Lines are generated from the kinematic (pure-rolling) frequencies; real bearings slip 1-2 % and a
// record's nominal speed may be off by a few percent, so every metric searches a +/- tolerance
// window around the kinematic position (MATLAB faultBandMetrics semantics: peak level, peak
// frequency and band power per line).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/bearing.h"

namespace spallkit::dsp {

enum class FaultComponent { kOuterRace, kInnerRace, kRollingElement, kCage };

// All four components, in the order used by reports.
inline constexpr FaultComponent kFaultComponents[] = {FaultComponent::kOuterRace,
                                                      FaultComponent::kInnerRace,
                                                      FaultComponent::kRollingElement,
                                                      FaultComponent::kCage};

// Stable names used in JSON and verdicts: "outer_race", "inner_race", "rolling_element", "cage".
const char* ComponentName(FaultComponent component);
// Symbol of the family's fundamental: "BPFO", "BPFI", "f_b", "f_c".
const char* ComponentSymbol(FaultComponent component);

// One expected line: harmonic k of the fundamental plus `sideband` times the sideband spacing,
// or, for the rolling element's spin series, the half order (k - 1/2) f0.
struct FaultLine {
  int harmonic = 1;         // k >= 1
  int sideband = 0;         // -1, 0 or +1
  bool half_order = false;  // at (k - 1/2) f0: 1, 3, 5 x BSF of a roller spall (f0 = f_b = 2 BSF)
  double nominal_hz = 0.0;  // kinematic position order() f0 + sideband f_sb
  std::string label;        // "2xBPFI", "2xBPFI-f_r", "1xf_b+f_c", "0.5xf_b"
  bool is_sideband() const { return sideband != 0; }
  double order() const { return half_order ? harmonic - 0.5 : harmonic; }
};

struct FaultFamily {
  FaultComponent component = FaultComponent::kOuterRace;
  double fundamental_hz = 0.0;   // f0: BPFO, BPFI, f_b or f_c (kinematic)
  double sideband_hz = 0.0;      // f_r (inner race), f_c (rolling element, optional outer), 0 none
  std::vector<FaultLine> lines;  // harmonics 1..N first (then the half orders), then sidebands

  // Highest line frequency (Hz, kinematic).
  double MaxLineHz() const;
};

struct FaultBandOptions {
  int harmonics = 5;                  // N: harmonics 1..N of each fundamental
  bool sidebands = true;              // inner race +/- f_r, rolling element +/- f_c
  bool outer_race_sidebands = false;  // BPFO +/- f_c (listing only; not expected for a fixed fault)
  // Rolling element: also the spin series (k - 1/2) f_b, k = 1..N (1, 3, 5 x BSF). A roller
  // spall strikes the outer and the inner race in turn, once each per roller revolution; the two
  // impacts differ (curvature, load, path to the sensor), so the record is periodic at BSF, not
  // only at f_b = 2 BSF.
  bool rolling_element_spin_series = true;
  double tolerance = 0.02;  // relative half-width of each search window (slip, speed error)

  bool IsValid(std::string* error) const;
};

// The four families for a bearing running at `f.shaft_hz`.
std::vector<FaultFamily> MakeFaultFamilies(const BearingFrequencies& f,
                                           const FaultBandOptions& options = {});

// Metrics of one line in a one-sided spectrum sampled at k * resolution_hz, k = 0, 1, ...
struct LineMetric {
  FaultLine line;
  double low_hz = 0.0, high_hz = 0.0;  // search window: nominal * (1 -/+ tolerance)
  double peak_hz = 0.0;                // interpolated frequency of the largest bin in the window
  double peak_level = 0.0;             // level of that bin
  double band_power = 0.0;             // sum of level over the window's bins
  bool in_range = true;                // false if the window lies (partly) beyond the spectrum
};

struct FaultBandMetrics {
  FaultComponent component = FaultComponent::kOuterRace;
  std::vector<LineMetric> lines;
  double total_band_power = 0.0;
};

// faultBandMetrics-style table for every family. `level` is a power-like spectrum (e.g. SES).
std::vector<FaultBandMetrics> ComputeFaultBandMetrics(std::span<const double> level,
                                                      double resolution_hz,
                                                      const std::vector<FaultFamily>& families,
                                                      double tolerance);

// Sub-bin peak position: Gaussian interpolation (parabola through the logs of the bin and its two
// neighbours), exact for a Gaussian-shaped peak and within a few % of a bin for Hann/rectangular
// peaks. Returns the frequency in Hz; falls back to the bin centre at the spectrum edges or when a
// neighbour is not positive.
double InterpolatePeakHz(std::span<const double> level, int bin, double resolution_hz);

}  // namespace spallkit::dsp
