// Bearing options shared by `spall frequencies` and `spall diagnose`: either a catalogue name
// (--bearing) or the explicit geometry (--elements, --element-diameter-mm, --pitch-diameter-mm,
// --contact-angle-deg).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "core/bearing.h"
#include "core/error.h"

namespace spallkit::apps {

struct BearingOptions {
  std::string bearing;
  int elements = 0;
  double element_diameter_mm = 0.0;
  double pitch_diameter_mm = 0.0;
  double contact_angle_deg = 0.0;

  // The explicit-geometry options, to tell "given" from "left at its default".
  CLI::Option* explicit_options[4] = {nullptr, nullptr, nullptr, nullptr};

  void Add(CLI::App& sub) {
    sub.add_option("--bearing", bearing, "catalogue bearing (N205EM, 6205, 6203)");
    explicit_options[0] =
        sub.add_option("--elements", elements, "number of rolling elements (explicit geometry)");
    explicit_options[1] =
        sub.add_option("--element-diameter-mm", element_diameter_mm, "roller/ball diameter, mm");
    explicit_options[2] =
        sub.add_option("--pitch-diameter-mm", pitch_diameter_mm, "pitch diameter, mm");
    explicit_options[3] =
        sub.add_option("--contact-angle-deg", contact_angle_deg, "contact angle, degrees");
  }

  // Throws InputError when neither or both ways are given, or the geometry is not physical.
  BearingGeometry Geometry() const {
    std::string given;  // the explicit-geometry options on the command line
    for (const CLI::Option* opt : explicit_options)
      if (opt && opt->count() > 0) given += (given.empty() ? "" : ", ") + opt->get_name();
    const bool custom = !given.empty() || elements > 0 || element_diameter_mm > 0 ||
                        pitch_diameter_mm > 0 || contact_angle_deg != 0;
    if (!bearing.empty() && custom)
      throw InputError("give either --bearing or the explicit geometry, not both (--bearing " +
                       bearing + " with " + (given.empty() ? "explicit geometry" : given) + ")");
    if (!bearing.empty()) return CatalogBearing(bearing);
    if (!custom)
      throw InputError(
          "no bearing: give --bearing NAME or --elements, --element-diameter-mm, "
          "--pitch-diameter-mm [--contact-angle-deg]");
    return CustomBearing(elements, element_diameter_mm, pitch_diameter_mm, contact_angle_deg);
  }
};

}  // namespace spallkit::apps
