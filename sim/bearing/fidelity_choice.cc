#include "sim/bearing/fidelity_choice.h"

#include <algorithm>
#include <sstream>

#include "core/error.h"

namespace spallkit::sim {

const std::vector<RungErrors>& MeasuredRungErrors() {
  // datasets/reference/ladder-quick.json (spall bench ladder --quick, the paper's friction with
  // the lubricant traction law): the largest error over its three scenes against hybrid 1 mm,
  // the finest rung it runs; the hybrid rung is its 2 mm run (FidelityChoiceTest checks these
  // against the stored file). The full FE is the model the others approximate: no measured error
  // of its own; its cost is the 1.0 mm figure of docs/PERFORMANCE.md.
  static const std::vector<RungErrors> kRungs = {
      {Fidelity::kLumped, 0.00235, 0.00273, 0.00271, 0.1060, 2.83},
      {Fidelity::kHybrid, 0.00529, 0.00373, 0.00372, 0.03392, 74.5},
      {Fidelity::kFe, 0.0, 0.0, 0.0, 0.0, 1350.0},
  };
  return kRungs;
}

std::string FullFeUnavailable(const Scene& scene) {
  if (scene.friction.model != contact::TractionModel::kCoulomb)
    return "friction.model = \"ehl\" (the full FE has Coulomb friction only)";
  for (std::size_t i = 0; i < scene.defects.size(); ++i) {
    const Defect& d = scene.defects[i];
    const std::string name = "defects." + std::to_string(i);
    if (d.ShorterThan(scene.geometry.thickness_m))
      return name + " is shorter than the roller (the FE section is 2-D)";
    if (d.UnresolvedBy(scene.mesh.contact_size_m))
      return name +
             " is smaller than the contact mesh allows (width >= 1.5 and depth >= 1 "
             "element of mesh.contact_size_mm)";
  }
  return "";
}

namespace {
bool AsksForField(const Scene& scene) { return Asks(scene.outputs, Output::kField); }
}  // namespace

std::string AutoFidelityConflict(const Scene& scene) {
  if (!AsksForField(scene)) return "";
  const std::string why = FullFeUnavailable(scene);
  if (why.empty()) return "";
  return "\"field\" asks for the stress field of every part, which only model.fidelity = \"fe\" "
         "records, but the full FE cannot run this scene: " +
         why + "; drop \"field\" or set model.fidelity = \"hybrid\" (its housing's field)";
}

FidelityChoice ChooseFidelity(const Scene& scene) {
  FidelityChoice c;
  if (scene.model.fidelity != Fidelity::kAuto) {
    c.fidelity = scene.model.fidelity;
    c.reason = std::string("fidelity ") + FidelityName(c.fidelity) + " (set in the scene)";
    return c;
  }
  if (const std::string conflict = AutoFidelityConflict(scene); !conflict.empty())
    throw InputError(scene.source + ": fidelity auto: " + conflict);
  const std::string fe_unavailable = FullFeUnavailable(scene);
  if (AsksForField(scene)) {
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
    if (r.fidelity == Fidelity::kFe && !fe_unavailable.empty()) {
      c.fidelity = Fidelity::kHybrid;
      os << "fidelity auto -> hybrid: no cheaper rung meets run.tolerance and the full FE cannot "
            "run this scene: "
         << fe_unavailable;
      break;
    }
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
