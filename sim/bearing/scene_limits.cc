#include "sim/bearing/scene_limits.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/constants.h"
#include "core/format.h"
#include "sim/quasistatic/harris_jones.h"

namespace spallkit::sim {
namespace {

double PhysicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * page : 8.0e9;
}

// Plane-strain contact modulus E* of two bodies: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
double ContactModulus(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus_pa +
                (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus_pa);
}

LoadDistributionOptions SceneLoadOptions(const Scene& scene, double load) {
  LoadDistributionOptions o;
  o.radial_load_n = load;
  o.inner_ring_speed_rad_s = scene.operation.inner_ring_speed_rad_s;
  o.roller_length_m = scene.geometry.thickness_m;
  o.diametral_clearance_m = scene.geometry.diametral_clearance_m;
  o.phase_rad = 0.0;  // roller on the load line: the largest Q_max over phases
  o.roller_density_kg_m3 = scene.materials.roller.density_kg_m3;
  return o;
}

}  // namespace

double PeakContactStress(const Scene& scene) {
  return PeakContactStress(scene, scene.operation.radial_load_n);
}

double PeakContactStress(const Scene& scene, double load) {
  if (!(load > 0)) return 0.0;
  LoadDistributionSummary s;
  SolveLoadDistribution(SceneLoadOptions(scene, load), scene.geometry.bearing, &s);
  if (!s.IsSolutionUsable()) return HUGE_VAL;
  // The inner contact is the more curved one (convex race).
  return HertzLinePressure(std::max(s.q_max_inner_n, s.q_max_n),
                           scene.geometry.thickness_m,
                           0.5 * scene.geometry.bearing.element_diameter_m,
                           0.5 * scene.geometry.bearing.inner_raceway_diameter_m,
                           ContactModulus(scene.materials.roller, scene.materials.inner_ring));
}

double InnerRingRadialPeriod(const Scene& scene) {
  const double load = scene.operation.radial_load_n;
  if (!(load > 0)) return 0.0;
  LoadDistributionSummary s;
  SolveLoadDistribution(SceneLoadOptions(scene, load), scene.geometry.bearing, &s);
  if (!s.IsSolutionUsable() || !(s.radial_stiffness_n_m > 0)) return 0.0;
  const SceneGeometry& g = scene.geometry;
  const double r_race = 0.5 * g.bearing.inner_raceway_diameter_m;
  const double r_bore = 0.5 * g.inner_ring_bore_diameter_m;
  const double mass = scene.materials.inner_ring.density_kg_m3 * g.ring_width_m * kPi *
                      (r_race * r_race - r_bore * r_bore);
  return 2.0 * kPi * std::sqrt(mass / s.radial_stiffness_n_m);
}

double DynamicLoadFactor(const Scene& scene) {
  if (!(scene.operation.radial_load_n > 0)) return 1.0;
  const double ramp = scene.operation.load_ramp_s;
  if (!(ramp > 0)) return 2.0;  // a step: no period needed
  const double period = InnerRingRadialPeriod(scene);
  if (!(period > 0)) return 2.0;
  return std::min(2.0, 1.0 + period / (kPi * ramp));
}

double EstimatedElements(const Scene& scene) {
  const SceneGeometry& g = scene.geometry;
  const double h = scene.mesh.size_m;
  auto annulus = [](double d_in, double d_out) {
    return 0.25 * kPi * (d_out * d_out - d_in * d_in);
  };
  double area = annulus(g.bearing.outer_raceway_diameter_m, g.outer_ring_outer_diameter_m);
  if (scene.model.fidelity == Fidelity::kFe) {
    const double r = 0.5 * g.bearing.element_diameter_m;
    area += annulus(g.inner_ring_bore_diameter_m, g.bearing.inner_raceway_diameter_m);
    area += g.bearing.num_elements * kPi * r * r;
    area += 0.5 * annulus(g.cage_inner_diameter_m, g.cage_outer_diameter_m);  // webs
  }
  // The adapter grades from h at the seat to adapter_size_m away from it.
  const double adapter = g.adapter_width_m * g.adapter_height_m;
  return area / (h * h) + adapter / (h * scene.mesh.adapter_size_m);
}

double ResolvedRateHz(const Scene& scene) {
  // The slowest bar wave speed of the meshed parts over the largest element: an upper bound of
  // the rate the explicit step (about element size / dilatational speed) samples.
  auto bar_speed = [](const Material& m) {
    return std::sqrt(m.youngs_modulus_pa / m.density_kg_m3);
  };
  const SceneMaterials& mat = scene.materials;
  double c = std::min(bar_speed(mat.outer_ring), bar_speed(mat.adapter));
  if (scene.model.fidelity == Fidelity::kFe)
    c = std::min({c, bar_speed(mat.inner_ring), bar_speed(mat.roller), bar_speed(mat.cage)});
  return c / std::max(scene.mesh.size_m, scene.mesh.adapter_size_m);
}

double EstimatedResultBytes(const Scene& scene) {
  const double samples = std::floor(scene.run.duration_s * scene.run.output_rate_hz) + 1.0;
  const double z = scene.geometry.bearing.num_elements;
  double channels = 0;
  for (const Sensor& s : scene.sensors) channels += static_cast<double>(s.directions.size());
  double columns = 1;  // time
  for (const Output out : scene.outputs) {
    if (out == Output::kContactForces) columns += 3 * z;
    if (out == Output::kCage) columns += 2;
    if (out == Output::kRollers) columns += 2 * z;
    if (out == Output::kEnergy) columns += 8;
    if (out == Output::kField && scene.model.fidelity != Fidelity::kLumped)
      columns += EstimatedElements(scene) * scene.run.field_rate_hz / scene.run.output_rate_hz;
    if (out == Output::kAcceleration) columns += channels;
  }
  // Doubled: the results are copied once more when written.
  return 2.0 * 8.0 * samples * columns;
}

std::optional<SceneLimitViolation> FindSceneLimitViolation(const Scene& scene,
                                                           const SceneLimits& limits) {
  if (!(scene.run.duration_s <= limits.max_duration_s))
    return SceneLimitViolation{"run.duration_s",
                               "must be at most " + FormatNumber("%.3g", limits.max_duration_s) +
                                   " s of simulated time (got " +
                                   FormatNumber("%.3g", scene.run.duration_s) + ")"};
  const double ci = scene.solver.checkpoint_interval_s;
  if (ci > 0 && !(scene.run.duration_s / ci <= 1e5))
    return SceneLimitViolation{"solver.checkpoint_interval_s",
                               FormatNumber("%.3g", ci) + " s gives " +
                                   FormatNumber("%.3g", scene.run.duration_s / ci) +
                                   " checkpoints over run.duration_s, more than 1e+05 (each "
                                   "writes the whole state)"};
  const double max_bytes =
      limits.max_result_bytes > 0 ? limits.max_result_bytes : 0.5 * PhysicalMemoryBytes();
  const double bytes = EstimatedResultBytes(scene);
  if (!(bytes <= max_bytes))
    return SceneLimitViolation{
        "run.output_rate_hz",
        "run.duration_s x run.output_rate_hz = " +
            FormatNumber("%.3g", std::floor(scene.run.duration_s * scene.run.output_rate_hz) + 1) +
            " samples per output need about " + FormatNumber("%.3g", bytes / 1e9) +
            " GB for the results, more than the " + FormatNumber("%.3g", max_bytes / 1e9) +
            " GB allowed (half of this machine's memory); lower the rate or the duration"};
  const double resolved_hz = ResolvedRateHz(scene);
  if (!(scene.run.output_rate_hz <= resolved_hz))
    return SceneLimitViolation{
        "run.output_rate_hz",
        FormatNumber("%.3g", scene.run.output_rate_hz) +
            " Hz is above what the mesh resolves: wave speed / "
            "element size = " +
            FormatNumber("%.3g", resolved_hz) +
            " Hz (the simulation's own step rate is of that order; samples would repeat)"};
  const double elements = EstimatedElements(scene);
  if (!(elements <= limits.max_elements))
    return SceneLimitViolation{"mesh.size_mm",
                               "about " + FormatNumber("%.3g", elements) + " elements at " +
                                   FormatNumber("%.3g", scene.mesh.size_m * 1e3) +
                                   " mm, more than " + FormatNumber("%.3g", limits.max_elements) +
                                   "; use a coarser mesh"};
  const double dynamic = DynamicLoadFactor(scene);
  const double stress = PeakContactStress(scene, dynamic * scene.operation.radial_load_n);
  if (!(stress <= limits.max_contact_stress_pa))
    return SceneLimitViolation{
        "operation.radial_load_n",
        FormatNumber("%.6g", scene.operation.radial_load_n) + " N" +
            (dynamic > 1.01 ? " (peaking at " + FormatNumber("%.3g", dynamic) +
                                  " x when applied over operation.load_ramp_s = " +
                                  FormatNumber("%.3g", scene.operation.load_ramp_s * 1e3) + " ms)"
                            : std::string()) +
            " gives a Hertz contact stress of " + FormatNumber("%.3g", stress / 1e9) +
            " GPa at the most loaded roller, above " +
            FormatNumber("%.3g", limits.max_contact_stress_pa / 1e9) +
            " GPa (ISO 76 static load rating: the races deform plastically, the models are "
            "elastic)"};
  return std::nullopt;
}

}  // namespace spallkit::sim
