#include "sim/bearing/fidelity_choice.h"

#include <sstream>

#include "core/error.h"

namespace spallkit::sim {

const std::vector<RungErrors>& MeasuredRungErrors() {
  // spall bench ladder --quick (docs/PERFORMANCE.md, "Fidelity ladder"): the largest error over
  // its scenes against the finest rung run there.
  static const std::vector<RungErrors> kRungs = {
      {Fidelity::kLumped, 0.01, 0.01, 0.01, 0.15, 2.0},
      {Fidelity::kHybrid, 0.005, 0.005, 0.005, 0.05, 45.0},
      {Fidelity::kFe, 0.0, 0.0, 0.0, 0.0, 4300.0},
  };
  return kRungs;
}

FidelityChoice ChooseFidelity(const Scene& scene) {
  FidelityChoice c;
  if (scene.model.fidelity != "auto") {
    if (!ParseFidelity(scene.model.fidelity, &c.fidelity))
      throw InputError(scene.source + ": model.fidelity: unknown \"" + scene.model.fidelity + "\"");
    c.reason = std::string("fidelity ") + FidelityName(c.fidelity) + " (set in the scene)";
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
  s.model.fidelity = FidelityName(c.fidelity);
  if (choice) *choice = c;
  return s;
}

}  // namespace spallkit::sim
