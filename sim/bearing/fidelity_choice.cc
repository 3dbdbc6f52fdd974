#include "sim/bearing/fidelity_choice.h"

#include <algorithm>
#include <sstream>

namespace spallkit::sim {

const std::vector<RungErrors>& MeasuredRungErrors() {
  // datasets/reference/ladder-quick.json (spall bench ladder --quick): the largest error over its
  // three scenes against hybrid 1 mm, the finest rung it runs; the hybrid rung is its 2 mm run.
  // The full FE is the model the others approximate: no measured error of its own; its cost is
  // the 1.0 mm figure of docs/PERFORMANCE.md. Wall times: the ladder's, on a loaded machine.
  static const std::vector<RungErrors> kRungs = {
      {Fidelity::kLumped, 0.0104, 0.0064, 0.0064, 0.111, 15.8},
      {Fidelity::kHybrid, 0.0074, 0.0074, 0.0074, 0.0138, 246.0},
      {Fidelity::kFe, 0.0, 0.0, 0.0, 0.0, 1350.0},
  };
  return kRungs;
}

FidelityChoice ChooseFidelity(const Scene& scene) {
  FidelityChoice c;
  if (scene.model.fidelity != Fidelity::kAuto) {
    c.fidelity = scene.model.fidelity;
    c.reason = std::string("fidelity ") + FidelityName(c.fidelity) + " (set in the scene)";
    return c;
  }
  if (std::find(scene.outputs.begin(), scene.outputs.end(), Output::kField) !=
      scene.outputs.end()) {
    c.fidelity = Fidelity::kFe;
    c.reason =
        "fidelity auto -> fe: run.outputs asks for the stress field, which only the full FE has "
        "for "
        "every part (the hybrid meshes the outer ring and adapter alone)";
    return c;
  }
  const SceneTolerance& tol = scene.run.tolerance;
  std::ostringstream os;
  os.precision(3);
  for (const RungErrors& r : MeasuredRungErrors()) {
    const bool meets = r.f_b <= tol.f_b && r.f_c <= tol.f_c && r.cage_slip <= tol.cage_slip &&
                       r.roller_load <= tol.roller_load;
    if (!meets && r.fidelity != Fidelity::kFe) continue;
    c.fidelity = r.fidelity;
    os << "fidelity auto -> " << FidelityName(r.fidelity) << ": measured errors f_b " << 100 * r.f_b
       << " %, f_c " << 100 * r.f_c << " %, cage slip " << 100 * r.cage_slip << " pp, roller load "
       << 100 * r.roller_load << " % against run.tolerance " << 100 * tol.f_b << " / "
       << 100 * tol.f_c << " / " << 100 * tol.cage_slip << " / " << 100 * tol.roller_load << "; ~"
       << r.wall_s_per_simulated_s << " s wall per simulated s";
    if (!meets) os << " (no cheaper rung meets the tolerance)";
    break;
  }
  c.reason = os.str();
  return c;
}

Scene WithChosenFidelity(const Scene& scene, FidelityChoice* choice) {
  const FidelityChoice c = ChooseFidelity(scene);
  Scene s = scene;
  s.model.fidelity = c.fidelity;
  if (choice) *choice = c;
  return s;
}

}  // namespace spallkit::sim
