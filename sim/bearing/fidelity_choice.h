// model.fidelity = "auto": the cheapest rung of the fidelity ladder whose measured error meets
// what the scene asks for (docs/BEARING_MODEL.md "Choosing the fidelity"; docs/PERFORMANCE.md
// "Fidelity ladder").
//
// The needs of a scene: its [run.tolerance] (errors allowed on f_b, f_c, the cage slip and the
// largest roller load) and its [run] outputs (contact forces, acceleration, cage, rollers and
// energy are made by every rung; the stress field of every part only by the full FE, which is
// then chosen whatever the tolerance). The rungs' errors are the bounds `spall bench
// ladder` measured against the finest model (MeasuredRungErrors); a rung is chosen when each of
// its bounds is within the tolerance, cheapest first: lumped, hybrid, fe. "auto" is the scene
// default.
#pragma once

#include <string>
#include <vector>

#include "sim/bearing/bearing_model.h"
#include "sim/bearing/scene.h"

namespace spallkit::sim {

// Largest error of a rung over the ladder's scenes against the finest model, as fractions
// (cage_slip: absolute difference of the slip ratio), and its cost.
struct RungErrors {
  Fidelity fidelity = Fidelity::kFe;
  double f_b = 0, f_c = 0, cage_slip = 0, roller_load = 0;
  double wall_s_per_simulated_s = 0;  // one thread, paper scene, 1200 rpm
};

// The ladder's measured bounds, cheapest rung first (the command that reproduces them is in
// docs/PERFORMANCE.md).
const std::vector<RungErrors>& MeasuredRungErrors();

struct FidelityChoice {
  Fidelity fidelity = Fidelity::kFe;
  std::string reason;  // one line: which rung and why
};

// Why the full FE cannot run the scene ("" when it can): the lubricant traction law, a spall
// shorter than the roller, or a spall too small for the contact mesh.
std::string FullFeUnavailable(const Scene& scene);
// For model.fidelity = "auto": why no model can run the scene ("" when one can): the stress
// field, which only the full FE records, asked for where the full FE is unavailable.
std::string AutoFidelityConflict(const Scene& scene);

// The fidelity the scene runs at: its model.fidelity, or for "auto" the choice above (never the
// full FE where FullFeUnavailable). Throws InputError where AutoFidelityConflict.
FidelityChoice ChooseFidelity(const Scene& scene);

// The scene with model.fidelity set to ChooseFidelity's choice (effective_toml unchanged: the
// scene file still says "auto").
Scene WithChosenFidelity(const Scene& scene, FidelityChoice* choice = nullptr);

}  // namespace spallkit::sim
