#include "core/bearing.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "core/error.h"

namespace spallkit {
namespace {

constexpr double kMm = 1e-3;

BearingGeometry Make(
    const char* name, int z, double d_mm, double dm_mm, double di_mm, double do_mm) {
  BearingGeometry g;
  g.name = name;
  g.num_elements = z;
  g.element_diameter_m = d_mm * kMm;
  g.pitch_diameter_m = dm_mm * kMm;
  g.inner_raceway_diameter_m = di_mm * kMm;
  g.outer_raceway_diameter_m = do_mm * kMm;
  return g;
}

std::string Upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
  return s;
}

}  // namespace

void BearingGeometry::Validate() const {
  if (num_elements < 3) throw InputError("bearing: number of rolling elements must be >= 3");
  if (!(element_diameter_m > 0) || !std::isfinite(element_diameter_m))
    throw InputError("bearing: element diameter must be a finite number > 0");
  if (!(pitch_diameter_m > element_diameter_m) || !std::isfinite(pitch_diameter_m))
    throw InputError("bearing: pitch diameter must be finite and exceed the element diameter");
  if (!(std::abs(contact_angle_rad) < std::numbers::pi / 2))
    throw InputError("bearing: contact angle must be in (-90, 90) degrees");
  if (num_elements * element_diameter_m >= std::numbers::pi * pitch_diameter_m)
    throw InputError("bearing: " + std::to_string(num_elements) +
                     " elements do not fit on the pitch circle");
}

std::vector<std::string> CatalogNames() { return {"N205EM", "6205", "6203"}; }

BearingGeometry CatalogBearing(const std::string& name) {
  const std::string key = Upper(name);
  // N205EM as modelled in the paper: raceways 32/45 mm, 6.5 mm rollers, 13 rollers, d_m 38.5 mm.
  if (key == "N205EM") return Make("N205EM", 13, 6.5, 38.5, 32.0, 45.0);
  // SKF 6205-2RS JEM, CWRU drive end: 9 balls of 7.940 mm (0.3126 in), pitch 39.040 mm (1.537 in).
  if (key == "6205") return Make("6205", 9, 7.940, 39.040, 39.040 - 7.940, 39.040 + 7.940);
  // SKF 6203-2RS JEM, CWRU fan end: 8 balls of 6.7462 mm (0.2656 in), pitch 28.4988 mm (1.122 in).
  if (key == "6203") return Make("6203", 8, 6.7462, 28.4988, 28.4988 - 6.7462, 28.4988 + 6.7462);
  std::string known;
  for (const auto& n : CatalogNames()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown bearing '" + name + "' (known: " + known +
                   "; or give --elements, --element-diameter-mm, --pitch-diameter-mm)");
}

BearingGeometry CustomBearing(int num_elements,
                              double element_diameter_mm,
                              double pitch_diameter_mm,
                              double contact_angle_deg) {
  BearingGeometry g;
  g.name = "custom";
  g.num_elements = num_elements;
  g.element_diameter_m = element_diameter_mm * kMm;
  g.pitch_diameter_m = pitch_diameter_mm * kMm;
  g.contact_angle_rad = contact_angle_deg * std::numbers::pi / 180.0;
  g.inner_raceway_diameter_m = g.pitch_diameter_m - g.element_diameter_m;
  g.outer_raceway_diameter_m = g.pitch_diameter_m + g.element_diameter_m;
  g.Validate();
  return g;
}

BearingFrequencies ComputeFrequencies(const BearingGeometry& bearing, double shaft_hz) {
  bearing.Validate();
  if (!(shaft_hz > 0) || !std::isfinite(shaft_hz))
    throw InputError("shaft speed must be a positive number (got " + std::to_string(shaft_hz) +
                     " Hz)");
  const double gamma =
      bearing.element_diameter_m * std::cos(bearing.contact_angle_rad) / bearing.pitch_diameter_m;
  BearingFrequencies f;
  f.shaft_hz = shaft_hz;
  f.cage_hz = 0.5 * shaft_hz * (1.0 - gamma);
  f.roller_spin_hz = bearing.pitch_diameter_m / (2.0 * bearing.element_diameter_m) * shaft_hz *
                     (1.0 - gamma * gamma);
  f.f_b_hz = 2.0 * f.roller_spin_hz;
  f.bpfo_hz = bearing.num_elements * f.cage_hz;
  f.bpfi_hz = bearing.num_elements * (shaft_hz - f.cage_hz);
  return f;
}

}  // namespace spallkit
