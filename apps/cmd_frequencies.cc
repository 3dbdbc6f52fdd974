// spall frequencies: kinematic fault frequencies of a bearing, in Hz and in orders (multiples of
// the shaft speed), with harmonics and the sidebands envelope analysis looks for.
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/bearing_options.h"
#include "apps/cli_guard.h"
#include "apps/command.h"
#include "core/bearing.h"
#include "core/error.h"
#include "dsp/fault_bands.h"

namespace {

struct Opts {
  spallkit::apps::BearingOptions bearing;
  double rpm = 0.0;
  int harmonics = 3;
  bool json = false;
};

int Run(const Opts& o) {
  using namespace spallkit;
  if (!(o.rpm > 0.0) || !std::isfinite(o.rpm))
    throw InputError("--rpm must be > 0 (got " + spallkit::apps::Number(o.rpm) + ")");
  if (o.harmonics < 1 || o.harmonics > 50)
    throw InputError("--harmonics must be in [1, 50] (got " + std::to_string(o.harmonics) + ")");
  const BearingGeometry g = o.bearing.Geometry();
  const BearingFrequencies f = ComputeFrequencies(g, o.rpm / 60.0);
  dsp::FaultBandOptions fbo;
  fbo.harmonics = o.harmonics;
  fbo.outer_race_sidebands = true;
  const auto families = dsp::MakeFaultFamilies(f, fbo);
  const double fr = f.shaft_hz;

  struct Base {
    const char* key;
    const char* name;
    double hz;
  };
  const Base bases[] = {
      {"shaft", "shaft f_r", f.shaft_hz},
      {"cage", "cage f_c (FTF)", f.cage_hz},
      {"roller_spin", "roller spin (BSF)", f.roller_spin_hz},
      {"f_b", "f_b = 2 x BSF (roller defect rate)", f.f_b_hz},
      {"bpfo", "BPFO (outer race)", f.bpfo_hz},
      {"bpfi", "BPFI (inner race)", f.bpfi_hz},
  };

  if (o.json) {
    nlohmann::ordered_json j;
    j["bearing"] = {{"name", g.name},
                    {"elements", g.num_elements},
                    {"element_diameter_mm", g.element_diameter_m * 1e3},
                    {"pitch_diameter_mm", g.pitch_diameter_m * 1e3},
                    {"contact_angle_deg", g.contact_angle_rad * 180.0 / M_PI}};
    j["rpm"] = o.rpm;
    j["f_b_convention"] = "f_b = 2 x roller spin (BSF); MATLAB bearingFaultBands' Fb = 1 x BSF";
    for (const auto& b : bases) j["frequencies"][b.key] = {{"hz", b.hz}, {"order", b.hz / fr}};
    for (const auto& fam : families) {
      nlohmann::ordered_json lines = nlohmann::ordered_json::array();
      for (const auto& l : fam.lines)
        lines.push_back({{"label", l.label},
                         {"harmonic", l.harmonic},
                         {"sideband", l.sideband},
                         {"hz", l.nominal_hz},
                         {"order", l.nominal_hz / fr}});
      j["families"][dsp::ComponentName(fam.component)] = lines;
    }
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }

  std::printf("bearing %s: %d elements, d = %.4g mm, d_m = %.4g mm, contact angle %.3g deg\n",
              g.name.c_str(),
              g.num_elements,
              g.element_diameter_m * 1e3,
              g.pitch_diameter_m * 1e3,
              g.contact_angle_rad * 180.0 / M_PI);
  std::printf("shaft speed %.6g rpm = %.6g Hz\n\n", o.rpm, fr);
  std::printf("  %-36s %12s %10s\n", "frequency", "Hz", "order");
  for (const auto& b : bases) std::printf("  %-36s %12.4f %10.5f\n", b.name, b.hz, b.hz / fr);
  std::printf(
      "\nNote: f_b is the rolling-element defect rate, 2 x roller spin; MATLAB's "
      "bearingFaultBands calls 1 x spin \"Fb\".\n");
  for (const auto& fam : families) {
    std::printf("\n%s family (%s):\n",
                dsp::ComponentName(fam.component),
                dsp::ComponentSymbol(fam.component));
    std::printf("  %-20s %12s %10s\n", "line", "Hz", "order");
    for (const auto& l : fam.lines)
      std::printf("  %-20s %12.4f %10.5f\n", l.label.c_str(), l.nominal_hz, l.nominal_hz / fr);
  }
  return 0;
}

spallkit::apps::Register reg(
    "frequencies",
    "Kinematic bearing fault frequencies (Hz and orders) with harmonics and sidebands",
    [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      o->bearing.Add(sub);
      sub.add_option("--rpm", o->rpm, "shaft speed, rpm")->required();
      sub.add_option("--harmonics", o->harmonics, "harmonics listed per family")
          ->capture_default_str();
      sub.add_flag("--json", o->json, "print one JSON object");
      return [o] { return Run(*o); };
    });

}  // namespace
