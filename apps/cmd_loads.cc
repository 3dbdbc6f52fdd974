// spall loads: Harris–Jones quasi-static roller loads of a radially loaded bearing.
//
//   spall loads --bearing N205EM --load-n 10000 --rpm 1200 --roller-length-mm 9
//               --clearance-mm 0.02 [--phase-deg 0] [--json]
//
// --clearance-mm is the DIAMETRAL clearance P_d (P_d/2 gap per roller). JSON keys (stable, see
// docs/BEARING_MODEL.md): bearing, radial_load_n, speed_rpm, roller_length_mm,
// diametral_clearance_mm, phase_deg, converged, iterations, delta_r_um, q_max_n,
// load_zone_half_angle_deg, epsilon, centrifugal_force_n, radial_stiffness_n_per_m,
// force_residual_n, rollers[{index, angle_deg, approach_um, load_inner_n, load_outer_n,
// deflection_inner_um, deflection_outer_um}].
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "apps/cli_guard.h"
#include "apps/command.h"
#include "core/bearing.h"
#include "core/error.h"
#include "sim/quasistatic/harris_jones.h"

namespace {

struct Opts {
  std::string bearing = "N205EM";
  double load_n = 10000.0;
  double rpm = 1200.0;
  double roller_length_mm = 9.0;
  double clearance_mm = 0.02;
  double phase_deg = 0.0;
  bool json = false;
};

constexpr double kDeg = std::numbers::pi / 180.0;

// Option ranges, each message naming the option (the library checks them again by its names).
void CheckOptions(const Opts& o, const spallkit::BearingGeometry& bearing) {
  using spallkit::InputError;
  const auto num = [](double v) { return spallkit::apps::Number(v); };
  if (!(o.load_n >= 0)) throw InputError("--load-n must be >= 0 N (got " + num(o.load_n) + ")");
  if (!(o.rpm >= 0 && o.rpm <= 1e5))
    throw InputError(
        "--rpm must be in [0, 100000] (the speed of the inner ring, as a scene's "
        "operation.speed_rpm; got " +
        num(o.rpm) + ")");
  if (!(o.roller_length_mm >= 0.1))
    throw InputError("--roller-length-mm must be >= 0.1 (got " + num(o.roller_length_mm) + ")");
  if (!(o.clearance_mm >= 0))
    throw InputError("--clearance-mm must be >= 0 (got " + num(o.clearance_mm) +
                     "; preload is not modelled)");
  if (!(std::abs(o.phase_deg) <= 360.0))
    throw InputError("--phase-deg must be in [-360, 360] (got " + num(o.phase_deg) + ")");
  const double d_mm = bearing.element_diameter_m * 1e3;
  if (!(o.clearance_mm < d_mm))
    throw InputError("--clearance-mm must be below the roller diameter, " + num(d_mm) +
                     " mm (got " + num(o.clearance_mm) + ")");
  if (!(o.roller_length_mm <= 10 * d_mm))
    throw InputError("--roller-length-mm must be at most 10 roller diameters, " + num(10 * d_mm) +
                     " mm (got " + num(o.roller_length_mm) + ")");
}

int Run(const Opts& o) {
  using namespace spallkit;
  const BearingGeometry bearing = CatalogBearing(o.bearing);
  CheckOptions(o, bearing);
  sim::LoadDistributionOptions opt;
  opt.radial_load_n = o.load_n;
  opt.inner_ring_speed_rad_s = o.rpm * 2.0 * std::numbers::pi / 60.0;
  opt.roller_length_m = o.roller_length_mm * 1e-3;
  opt.diametral_clearance_m = o.clearance_mm * 1e-3;
  opt.phase_rad = o.phase_deg * kDeg;
  sim::LoadDistributionSummary s;
  sim::SolveLoadDistribution(opt, bearing, &s);

  if (o.json) {
    nlohmann::ordered_json j;
    j["bearing"] = bearing.name;
    j["radial_load_n"] = o.load_n;
    j["speed_rpm"] = o.rpm;
    j["roller_length_mm"] = o.roller_length_mm;
    j["diametral_clearance_mm"] = o.clearance_mm;
    j["phase_deg"] = o.phase_deg;
    j["converged"] = s.IsSolutionUsable();
    j["iterations"] = s.iterations;
    j["delta_r_um"] = s.delta_r_m * 1e6;
    j["q_max_n"] = s.q_max_n;
    j["load_zone_half_angle_deg"] = s.load_zone_half_angle_rad / kDeg;
    j["epsilon"] = s.load_distribution_factor;
    j["centrifugal_force_n"] = s.centrifugal_force_n;
    j["radial_stiffness_n_per_m"] = s.radial_stiffness_n_m;
    j["force_residual_n"] = s.force_residual_n;
    auto& rollers = j["rollers"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < s.rollers.size(); ++i) {
      const auto& r = s.rollers[i];
      rollers.push_back({{"index", i},
                         {"angle_deg", r.angle_rad / kDeg},
                         {"approach_um", r.approach_m * 1e6},
                         {"load_inner_n", r.inner_load_n},
                         {"load_outer_n", r.outer_load_n},
                         {"deflection_inner_um", r.inner_deflection_m * 1e6},
                         {"deflection_outer_um", r.outer_deflection_m * 1e6}});
    }
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("%s\n", s.BriefReport().c_str());
    std::printf(
        "%5s %10s %12s %12s %12s\n", "roller", "psi_deg", "approach_um", "Q_inner_N", "Q_outer_N");
    for (std::size_t i = 0; i < s.rollers.size(); ++i) {
      const auto& r = s.rollers[i];
      std::printf("%5zu %10.2f %12.3f %12.1f %12.1f\n",
                  i,
                  r.angle_rad / kDeg,
                  r.approach_m * 1e6,
                  r.inner_load_n,
                  r.outer_load_n);
    }
  }
  // Past the static capacity the elastic line-contact law is extrapolated: say so.
  const double p0 = sim::HertzLinePressure(s.q_max_n,
                                           opt.roller_length_m,
                                           0.5 * bearing.element_diameter_m,
                                           0.5 * bearing.inner_raceway_diameter_m);
  if (s.IsSolutionUsable() && p0 > sim::kStaticCapacityStressPa)
    std::fprintf(stderr,
                 "spall: warning: Q_max %.4g N gives a Hertz contact stress of %.3g GPa, above the "
                 "%.0f GPa of the static load rating (ISO 76): plastic deformation, the elastic "
                 "contact law is extrapolated\n",
                 s.q_max_n,
                 p0 / 1e9,
                 sim::kStaticCapacityStressPa / 1e9);
  if (!s.IsSolutionUsable()) {
    std::fprintf(stderr, "spall: loads: %s\n", s.message.c_str());
    return 1;
  }
  return 0;
}

spallkit::apps::Register reg(
    "loads", "Harris-Jones quasi-static roller loads (radial load)", [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      sub.add_option("--bearing", o->bearing, "Catalogue bearing")->capture_default_str();
      sub.add_option("--load-n", o->load_n, "Radial load on the inner ring, N")
          ->capture_default_str();
      sub.add_option("--rpm", o->rpm, "Inner ring speed, rpm (outer ring fixed)")
          ->capture_default_str();
      sub.add_option("--roller-length-mm", o->roller_length_mm, "Effective roller length, mm")
          ->capture_default_str();
      sub.add_option("--clearance-mm",
                     o->clearance_mm,
                     "Diametral clearance P_d, mm (P_d/2 gap per roller)")
          ->capture_default_str();
      sub.add_option("--phase-deg", o->phase_deg, "Angle of roller 0 from the load line, deg")
          ->capture_default_str();
      sub.add_flag("--json", o->json, "Print one JSON object");
      return [o] { return Run(*o); };
    });

}  // namespace
