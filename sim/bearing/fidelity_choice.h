// model.fidelity = "auto": the cheapest rung of the fidelity ladder whose measured error meets
// what the scene asks for (docs/BEARING_MODEL.md "Choosing the fidelity"; docs/PERFORMANCE.md
// "Fidelity ladder").
//
// The needs of a scene: its [run.tolerance] (errors allowed on f_b, f_c, the cage slip and the
// largest roller load) and its [run] outputs (contact forces, acceleration, cage, rollers and
// energy are made by every rung; the stress field of every part only by the full FE, which is
// then chosen whatever the tolerance). The rungs' errors are the bounds `spall bench
// ladder` measured against the finest model, for the scene's mesh (RungBoundsFor); a rung is
// chosen when each of its bounds is within the tolerance, cheapest first: lumped, hybrid, fe.
// Where none is, the rung whose bounds come closest (the smallest largest error-to-tolerance
// ratio) runs and the reason says so. "auto" is the scene default.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sim/bearing/bearing_model.h"
#include "sim/bearing/scene.h"

namespace spallkit::sim {

// Largest error of a rung over the ladder's scenes against the finest model, as fractions
// (cage_slip: absolute difference of the slip ratio), and its cost.
struct RungErrors {
  Fidelity fidelity = Fidelity::kFe;
  double mesh_mm = 0;  // the mesh it was measured on (0: the lumped model, which has none)
  double f_b = 0, f_c = 0, cage_slip = 0, roller_load = 0;
  double wall_s_per_simulated_s = 0;  // one thread
  // The finest run of its ladder (the hybrid at 0.5 mm, the full FE at 0.25 mm): nothing finer
  // measures its errors, which are 0 here by definition, not by measurement.
  bool reference = false;
};

// The ladders' measured bounds, cheapest rung first: the lumped model and the hybrid at 2 and
// 1 mm from the full ladder (against the hybrid at 0.5 mm, its reference; the paper's friction
// with the lubricant traction law), then that reference; the full FE at 1 and 0.5 mm from the
// full-FE sub-ladder (against the full FE at 0.25 mm, Coulomb friction), then that reference.
// The commands that reproduce them are in docs/PERFORMANCE.md.
const std::vector<RungErrors>& MeasuredRungErrors();

// The bounds of a scene run at `fidelity` on the scene's mesh (mesh.size_mm), or nullopt where no
// ladder measured that model on such a mesh: the lumped model's own; for the hybrid on a mesh of
// 2 mm or finer the largest error measured on its meshes (they do not shrink with the mesh within
// the short runs' scatter); the full FE's at a measured mesh, between two measured meshes the
// larger error of the two (its errors do not shrink monotonically with the mesh), at 0.25 mm or
// finer the reference's. A mesh coarser than the coarsest measured one has no bound.
std::optional<RungErrors> RungBoundsFor(const Scene& scene, Fidelity fidelity);

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
