// Synthetic spalled-roller records (identify/synthetic_record.h) and a one-call identification
// for the identification tests.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/bearing.h"
#include "dsp/diagnose.h"
#include "identify/identify.h"
#include "identify/synthetic_record.h"

namespace spallkit::testing {

struct SpallSpec {
  int slot = 0;
  double width_mm = 1.38;
  double spin_phase_deg = 0.0;
};

inline identify::SyntheticRecordSpec RollerRecordSpec(double rpm,
                                                      double snr_db,
                                                      const std::vector<SpallSpec>& spalls,
                                                      unsigned seed = 1) {
  identify::SyntheticRecordSpec s;
  s.shaft_hz = rpm / 60.0;
  s.snr_db = snr_db;
  s.seed = seed;
  for (const auto& p : spalls) {
    identify::SyntheticRoller r;
    r.slot = p.slot;
    r.width_m = p.width_mm * 1e-3;
    r.spin_phase_rad = p.spin_phase_deg * 3.141592653589793 / 180.0;
    s.rollers.push_back(r);
  }
  return s;
}

// Diagnoses and identifies a record of an N205EM at rpm with the given radial load.
inline identify::Identification IdentifyRecord(const Record& record,
                                               double rpm,
                                               double load_n,
                                               identify::IdentifyOptions options = {}) {
  const BearingGeometry g = CatalogBearing("N205EM");
  const dsp::Diagnosis d = dsp::Diagnose(record, g, rpm / 60.0);
  options.radial_load_n = load_n;
  return identify::Identify(record, g, rpm / 60.0, d, options);
}

// Whether one of the identification's reasons contains `text`.
inline bool HasReason(const identify::Identification& id, std::string_view text) {
  for (const std::string& reason : id.reasons)
    if (reason.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace spallkit::testing
