// Bearing geometry, the built-in catalogue, and kinematic (pure-rolling) frequencies.
//
// Conventions (see docs/DIAGNOSIS.md):
//  - f_b is the ROLLING-ELEMENT DEFECT RATE = 2 x roller spin (BSF): a spall on a roller strikes
//    both races once per roller revolution. MATLAB's bearingFaultBands calls 1 x spin "Fb".
//  - f_c (FTF) is the cage rotation frequency, outer ring fixed, inner ring at the shaft speed.
//  - All values are SI inside: metres, radians, hertz. Catalogue entries are quoted in mm.
#pragma once

#include <string>
#include <vector>

namespace spallkit {

struct BearingGeometry {
  std::string name;                 // catalogue name or "custom"
  int num_elements = 0;             // Z, rollers or balls
  double element_diameter_m = 0.0;  // roller or ball diameter
  double pitch_diameter_m = 0.0;    // d_m
  double contact_angle_rad = 0.0;   // 0 for cylindrical roller and radial ball bearings
  // Raceway diameters: known for catalogue cylindrical roller bearings, else derived as
  // d_m -/+ element diameter.
  double inner_raceway_diameter_m = 0.0;
  double outer_raceway_diameter_m = 0.0;

  // Throws InputError naming the bad field when the geometry is not physical.
  void Validate() const;
};

// Names in the built-in catalogue: "N205EM", "6205", "6203".
std::vector<std::string> CatalogNames();
// Looks a bearing up by name (case-insensitive). Throws InputError listing the known names.
BearingGeometry CatalogBearing(const std::string& name);
// Explicit geometry in the units users type (mm, degrees). Validated.
BearingGeometry CustomBearing(int num_elements,
                              double element_diameter_mm,
                              double pitch_diameter_mm,
                              double contact_angle_deg);

// Kinematic frequencies for an inner ring turning at shaft_hz, outer ring fixed.
struct BearingFrequencies {
  double shaft_hz = 0.0;        // f_r
  double cage_hz = 0.0;         // f_c = FTF = f_r/2 (1 - gamma)
  double roller_spin_hz = 0.0;  // BSF, spin relative to the cage = d_m/(2 d) f_r (1 - gamma^2)
  double f_b_hz = 0.0;          // rolling-element defect rate = 2 x BSF
  double bpfo_hz = 0.0;         // Z f_c
  double bpfi_hz = 0.0;         // Z (f_r - f_c)
};

// gamma = d cos(alpha) / d_m. Throws InputError if shaft_hz <= 0.
BearingFrequencies ComputeFrequencies(const BearingGeometry& bearing, double shaft_hz);

}  // namespace spallkit
