#include "dsp/fault_bands.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace spallkit::dsp {

const char* ComponentName(FaultComponent component) {
  switch (component) {
    case FaultComponent::kOuterRace:
      return "outer_race";
    case FaultComponent::kInnerRace:
      return "inner_race";
    case FaultComponent::kRollingElement:
      return "rolling_element";
    case FaultComponent::kCage:
      return "cage";
  }
  return "unknown";
}

const char* ComponentSymbol(FaultComponent component) {
  switch (component) {
    case FaultComponent::kOuterRace:
      return "BPFO";
    case FaultComponent::kInnerRace:
      return "BPFI";
    case FaultComponent::kRollingElement:
      return "f_b";
    case FaultComponent::kCage:
      return "f_c";
  }
  return "?";
}

double FaultFamily::MaxLineHz() const {
  double m = 0.0;
  for (const auto& l : lines) m = std::max(m, l.nominal_hz);
  return m;
}

bool FaultBandOptions::IsValid(std::string* error) const {
  if (harmonics < 1 || harmonics > 50) {
    if (error) *error = "harmonics must be in 1..50 (got " + std::to_string(harmonics) + ")";
    return false;
  }
  if (!(tolerance >= 0.0 && tolerance <= 0.2)) {
    if (error) *error = "tolerance must be in [0, 0.2] (got " + std::to_string(tolerance) + ")";
    return false;
  }
  return true;
}

namespace {

FaultFamily MakeFamily(FaultComponent c,
                       double f0,
                       double fsb,
                       int harmonics,
                       const char* sb_name,
                       bool half_orders = false) {
  FaultFamily fam;
  fam.component = c;
  fam.fundamental_hz = f0;
  fam.sideband_hz = fsb;
  const std::string sym = ComponentSymbol(c);
  for (int k = 1; k <= harmonics; ++k) {
    FaultLine l;
    l.harmonic = k;
    l.nominal_hz = k * f0;
    l.label = std::to_string(k) + "x" + sym;
    fam.lines.push_back(l);
  }
  if (half_orders) {
    for (int k = 1; k <= harmonics; ++k) {
      FaultLine l;
      l.harmonic = k;
      l.half_order = true;
      l.nominal_hz = l.order() * f0;
      l.label = std::to_string(k - 1) + ".5x" + sym;
      fam.lines.push_back(l);
    }
  }
  if (fsb > 0.0) {
    for (int k = 1; k <= harmonics; ++k) {
      for (int s : {-1, +1}) {
        FaultLine l;
        l.harmonic = k;
        l.sideband = s;
        l.nominal_hz = k * f0 + s * fsb;
        l.label = std::to_string(k) + "x" + sym + (s < 0 ? "-" : "+") + sb_name;
        fam.lines.push_back(l);
      }
    }
  }
  return fam;
}

}  // namespace

std::vector<FaultFamily> MakeFaultFamilies(const BearingFrequencies& f,
                                           const FaultBandOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError("fault bands: " + error);
  const int n = options.harmonics;
  std::vector<FaultFamily> out;
  out.push_back(MakeFamily(FaultComponent::kOuterRace,
                           f.bpfo_hz,
                           options.outer_race_sidebands ? f.cage_hz : 0.0,
                           n,
                           "f_c"));
  out.push_back(MakeFamily(
      FaultComponent::kInnerRace, f.bpfi_hz, options.sidebands ? f.shaft_hz : 0.0, n, "f_r"));
  out.push_back(MakeFamily(FaultComponent::kRollingElement,
                           f.f_b_hz,
                           options.sidebands ? f.cage_hz : 0.0,
                           n,
                           "f_c",
                           options.rolling_element_spin_series));
  out.push_back(MakeFamily(FaultComponent::kCage, f.cage_hz, 0.0, n, "f_c"));
  return out;
}

std::vector<FaultBandMetrics> ComputeFaultBandMetrics(std::span<const double> level,
                                                      double resolution_hz,
                                                      const std::vector<FaultFamily>& families,
                                                      double tolerance) {
  if (!(resolution_hz > 0.0)) throw InputError("fault band metrics: resolution must be > 0 Hz");
  const int nbins = static_cast<int>(level.size());
  std::vector<FaultBandMetrics> out;
  for (const auto& fam : families) {
    FaultBandMetrics m;
    m.component = fam.component;
    for (const auto& line : fam.lines) {
      LineMetric lm;
      lm.line = line;
      lm.low_hz = line.nominal_hz * (1.0 - tolerance);
      lm.high_hz = line.nominal_hz * (1.0 + tolerance);
      int lo = static_cast<int>(std::ceil(lm.low_hz / resolution_hz));
      int hi = static_cast<int>(std::floor(lm.high_hz / resolution_hz));
      // A window narrower than a bin still looks at the nearest bin.
      if (hi < lo) lo = hi = static_cast<int>(std::lround(line.nominal_hz / resolution_hz));
      lo = std::max(lo, 1);  // never the DC bin
      if (hi >= nbins) {
        lm.in_range = false;
        hi = nbins - 1;
      }
      if (lo > hi) {
        lm.in_range = false;
        m.lines.push_back(lm);
        continue;
      }
      int best = lo;
      for (int i = lo; i <= hi; ++i) {
        lm.band_power += level[i];
        if (level[i] > level[best]) best = i;
      }
      lm.peak_level = level[best];
      lm.peak_hz = InterpolatePeakHz(level, best, resolution_hz);
      m.total_band_power += lm.band_power;
      m.lines.push_back(lm);
    }
    out.push_back(std::move(m));
  }
  return out;
}

double InterpolatePeakHz(std::span<const double> level, int bin, double resolution_hz) {
  const int n = static_cast<int>(level.size());
  if (bin <= 0 || bin >= n - 1) return bin * resolution_hz;
  const double a = level[bin - 1], b = level[bin], c = level[bin + 1];
  if (!(a > 0.0 && b > 0.0 && c > 0.0)) return bin * resolution_hz;
  const double la = std::log(a), lb = std::log(b), lc = std::log(c);
  const double denom = la - 2.0 * lb + lc;
  if (!(denom < 0.0)) return bin * resolution_hz;  // not a local maximum
  double delta = 0.5 * (la - lc) / denom;
  delta = std::clamp(delta, -0.5, 0.5);
  return (bin + delta) * resolution_hz;
}

}  // namespace spallkit::dsp
