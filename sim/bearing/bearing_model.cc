#include "sim/bearing/bearing_model.h"

#include <cmath>

#include "core/error.h"
#include "sim/bearing/lumped_model.h"
#include "sim/bearing/model_builder.h"

namespace spallkit::sim {

bool LumpedOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* m) {
    if (error) *error = m;
    return false;
  };
  if (!(fit_mesh_size_m > 0)) return fail("lumped model: fit_mesh_size_m must be > 0");
  if (!(fit_duration_s > 0)) return fail("lumped model: fit_duration_s must be > 0");
  if (!(fit_damping_ratio > 0)) return fail("lumped model: fit_damping_ratio must be > 0");
  if (!(time_step_safety > 0 && time_step_safety <= 1))
    return fail("lumped model: time_step_safety must be in (0, 1]");
  if (!(spalled_time_step_safety > 0 && spalled_time_step_safety <= time_step_safety))
    return fail("lumped model: spalled_time_step_safety must be in (0, time_step_safety]");
  if (!(spall_time_step_safety > 0 && spall_time_step_safety <= spalled_time_step_safety))
    return fail("lumped model: spall_time_step_safety must be in (0, spalled_time_step_safety]");
  if (!(fast_spall_time_step_safety > 0 && fast_spall_time_step_safety <= time_step_safety))
    return fail("lumped model: fast_spall_time_step_safety must be in (0, time_step_safety]");
  if (!(spall_step_min_load_fraction >= 0 && spall_step_min_load_fraction <= 1))
    return fail("lumped model: spall_step_min_load_fraction must be in [0, 1]");
  if (!(spall_step_linger_s >= 0 && spall_step_linger_s <= 0.1))
    return fail("lumped model: spall_step_linger_s must be in [0, 0.1]");
  if (!(spall_step_margin_rad >= 0 && spall_step_margin_rad <= 1))
    return fail("lumped model: spall_step_margin_rad must be in [0, 1]");
  if (!(spall_step_min_spin_ratio >= 0 && spall_step_min_spin_ratio <= 10))
    return fail("lumped model: spall_step_min_spin_ratio must be in [0, 10]");
  if (!(sensor_response_s >= 0 && sensor_response_s <= 0.1))
    return fail("lumped model: sensor_response_s must be in [0, 0.1]");
  if (!(sensor_sample_hz >= 1e3 && sensor_sample_hz <= 1e6))
    return fail("lumped model: sensor_sample_hz must be in [1e3, 1e6]");
  return true;
}

bool BearingModelOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* m) {
    if (error) *error = m;
    return false;
  };
  if (!(race_penalty_scale > 0)) return fail("bearing model: race_penalty_scale must be > 0");
  if (!(cage_penalty_scale > 0)) return fail("bearing model: cage_penalty_scale must be > 0");
  if (!(contact_damping_ratio >= 0 && contact_damping_ratio <= 1))
    return fail("bearing model: contact_damping_ratio must be in [0, 1]");
  if (!lumped.IsValid(error)) return false;
  return cage_guide.IsValid(error);
}

namespace {
// The options with what the scene sets for them: [model] contact_damping, for every contact;
// the cage's radial play (bearing.cage_radial_play_mm, always set: it is geometry).
BearingModelOptions WithSceneSettings(BearingModelOptions options, const Scene& scene) {
  options.cage_guide.radial_play_m = scene.geometry.cage_radial_play_m;
  if (scene.model.contact_damping)
    options.contact_damping_ratio = options.hybrid.contact_damping_ratio =
        *scene.model.contact_damping;
  return options;
}
}  // namespace

BearingModel::BearingModel(const Scene& scene, const BearingModelOptions& options)
    : scene_(scene), options_(WithSceneSettings(options, scene)) {
  std::string err;
  if (!options_.IsValid(&err)) throw InputError(err);
  speed_ = solver::RampedSpeed(scene_.operation.inner_ring_speed_rad_s, scene_.operation.ramp_s);
}

double BearingModel::TheoreticalCageSpeed(double t) const {
  const BearingGeometry& b = scene_.geometry.bearing;
  const double gamma = b.element_diameter_m * std::cos(b.contact_angle_rad) / b.pitch_diameter_m;
  return 0.5 * speed_(t) * (1.0 - gamma);
}

std::unique_ptr<BearingModel> MakeBearingModel(const Scene& scene,
                                               const BearingModelOptions& options) {
  const Fidelity f = scene.model.fidelity;
  if (f == Fidelity::kAuto)
    throw InputError(scene.source + ": model.fidelity: \"auto\" must be resolved to \"fe\", " +
                     "\"hybrid\" or \"lumped\" before a model is built (ChooseFidelity)");
  if (f == Fidelity::kLumped) return std::make_unique<LumpedBearingModel>(scene, options);
  return std::make_unique<FeBearingModel>(scene, options);
}

}  // namespace spallkit::sim
