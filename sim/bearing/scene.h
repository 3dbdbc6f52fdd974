// Scene files: one TOML file describes one bearing simulation (docs/SCENE.md is the reference).
//
// The file is read ONCE, here: units are converted to SI (mm -> m, rpm -> rad/s, deg -> rad),
// defaults are filled in (they reproduce the paper: N205EM, 10 kN, 1200 rpm, one 1.38 x 0.59 mm
// spall, 0.25 mm mesh), and every value is range-checked. Errors are InputError with one line
// "<file>:<line>: <key>: <what was expected>"; unknown keys are errors too, so a typo never
// silently falls back to a default.
//
// Scene::effective_toml is the scene after overrides and defaults, the exact input of a run
// (written to the HDF5 `scene` attribute so a result file can be re-run).
#pragma once

#include <toml++/toml.h>

#include <optional>
#include <string>
#include <vector>

#include "core/bearing.h"
#include "sim/contact/traction.h"

namespace spallkit::sim {

struct Material {
  double youngs_modulus_pa = 206e9;
  double poisson_ratio = 0.3;
  double density_kg_m3 = 7850.0;
};

// A rectangular (flat-bottomed) spall on a roller. The notch has chord width `width_m` at the
// roller surface, parallel side walls and a flat bottom `depth_m` below the intact surface at the
// spall's centre line. `angle_rad` is where its centre sits on the roller, measured
// counter-clockwise from the direction pointing radially OUT of the bearing (towards the outer
// race) at t = 0.
struct Defect {
  int roller = 0;
  double width_m = 1.38e-3;
  double depth_m = 0.59e-3;
  double angle_rad = 0.0;
  // Fillet radius of the spall's two rim edges (hybrid model; 0 = sharp, the FE mesher's edges
  // are sharp to the element size).
  double edge_radius_m = 0.0;
  // Axial length of the spall (hybrid model). Scene default: the section thickness, i.e. a
  // through-length spall as in the paper's 2-D model; shorter spalls leave an intact part of the
  // roller in contact (the hybrid model carries the two parts side by side).
  double length_m = 0.0;

  // What the full FE cannot mesh: a spall shorter than the roller (its section is 2-D), and a
  // spall its contact mesh does not resolve (width < 1.5, depth < 1 element of contact_size_m).
  bool ShorterThan(double thickness_m) const { return length_m < thickness_m * (1 - 1e-12); }
  bool UnresolvedBy(double contact_size_m) const {
    return width_m < 1.5 * contact_size_m || depth_m < contact_size_m;
  }
};

// Bearing section geometry. Raceway diameters are NOMINAL (zero clearance); the mesher opens
// the diametral clearance P_d by moving each raceway by P_d/4, so a centred roller has a gap of
// P_d/4 on each side and P_d/2 in total (Harris's convention, see quasistatic/harris_jones.h).
struct SceneGeometry {
  BearingGeometry bearing;    // Z, roller diameter, pitch and raceway diameters
  double thickness_m = 9e-3;  // 2-D section thickness = effective roller length
  // Axial width of the rings (and the adapter under them): the section thickness of the ring and
  // adapter elements, i.e. their bending stiffness and mass. Contacts, rollers and cage use
  // thickness_m. N205EM: 15 mm (ISO dimension series 02).
  double ring_width_m = 15e-3;
  double diametral_clearance_m = 20e-6;  // P_d
  double pocket_clearance_m = 0.2e-3;    // pocket width - roller diameter (total)
  // Roller-guided cage: each pocket holds its roller's centre within +- this of the pitch radius
  // (CageGuideOptions::radial_play_m); Table 1 gives no pocket shape, so 0.5 mm is assumed.
  double cage_radial_play_m = 0.5e-3;
  double outer_ring_outer_diameter_m = 52e-3;
  double inner_ring_bore_diameter_m = 25e-3;
  double cage_inner_diameter_m = 35.5e-3;  // Table 1 lists 17.75 / 21 mm: radii, see SCENE.md
  double cage_outer_diameter_m = 42e-3;
  double adapter_width_m = 40e-3;
  double adapter_height_m = 31e-3;  // at the centre line, bottom face to the seat
  double roller_phase_rad = 0.0;    // roller 0 angle from the load line (bottom, -y)
};

struct SceneMaterials {
  Material outer_ring, inner_ring, roller;
  Material cage{100e9, 0.36, 8920.0};  // brass
  Material adapter;                    // steel (Table 1 gives none; assumed)
};

struct SceneOperation {
  double radial_load_n = 10000.0;       // on the inner ring, towards -y (roller 0)
  double inner_ring_speed_rad_s = 0.0;  // from speed_rpm
  double ramp_s = 0.005;                // linear speed ramp from rest
  double load_ramp_s = 0.005;  // radial load's linear ramp from 0 at t = 0 (default ramp_s)
};

struct SceneFriction {
  double mu_static = 0.01;
  double mu_dynamic = 0.005;
  double decay_s_m = 0.0;  // mu = mu_d + (mu_s - mu_d) exp(-decay |v_rel|) (LS-DYNA DC)
  // Roller-race contacts of the rigid-roller models (hybrid, lumped): Coulomb with the mu above,
  // or the lubricant traction curve (sim/contact/traction.h); the cage pockets keep Coulomb.
  contact::TractionModel model = contact::TractionModel::kCoulomb;
  contact::EhlTraction ehl;
};

struct SceneDamping {
  double ratio = 0.02;  // fraction of critical at reference_hz (mass proportional)
  double reference_hz = 1000.0;
};

struct SceneMesh {
  double size_m = 0.25e-3;          // target element edge length
  double contact_size_m = 0.25e-3;  // edge length along contact surfaces (<= size_m refines)
  double adapter_size_m = 1.0e-3;   // largest element height in the adapter, away from the seat
};

// A sensor's measuring direction in the section's axes: x horizontal, y vertical.
enum class Axis { kX, kY };
// Scene-file names "x", "y".
const char* AxisName(Axis axis);
bool ParseAxis(const std::string& name, Axis* axis);

struct Sensor {
  std::string name;
  double x_m = 0.0, y_m = 0.0;   // position in the section (bearing centre at origin)
  std::vector<Axis> directions;  // measured directions (scene file: "x", "y")
};

// The error a run may have against the finest model ([run.tolerance]; Fidelity::kAuto
// picks the cheapest rung whose measured error meets it, sim/bearing/fidelity_choice.h).
struct SceneTolerance {
  double f_b = 0.01;          // relative error of the roller defect frequency
  double f_c = 0.03;          // relative error of the cage frequency
  double cage_slip = 0.01;    // absolute error of the cage slip ratio
  double roller_load = 0.15;  // relative error of the largest roller load
};

struct SceneRun {
  double duration_s = 0.2;
  double output_rate_hz = 20000.0;
  double field_rate_hz = 1000.0;  // stress field snapshots ("field"; <= output_rate_hz)
  SceneTolerance tolerance;
};

// Which model `spall simulate` builds (docs/BEARING_MODEL.md):
//  - kFe: every part meshed (level 4, the paper's model; sim/bearing/model_builder.h);
//  - kHybrid: outer ring + adapter meshed, rollers / cage / inner ring rigid bodies with exact
//    profiles and Palmgren contact (level 3, sim/bearing/hybrid_rollers.h). The mesh keys then
//    apply to the outer ring and adapter only and need not resolve the spalls;
//  - kLumped: the hybrid's rigid parts on a rigid outer ring with the housing's fitted
//    stiffness (sim/bearing/lumped_model.h); no mesh is stepped;
//  - kAuto: the cheapest of these whose measured error meets [run.tolerance]
//    (sim/bearing/fidelity_choice.h). A built model's fidelity is never kAuto.
enum class Fidelity { kFe, kHybrid, kLumped, kAuto };
// How the adapter under the outer ring is modelled. kElastic: FE (steel, scene
// materials.adapter); kRigid: every adapter node fixed, so the outer ring is held rigidly over the
// seat (Table 1 gives the adapter no material; docs/BEARING_MODEL.md, "Limits").
enum class AdapterModel { kElastic, kRigid };
// Roller-race contact of the full FE (kFe only): kSmooth (roller rims and raceways as cubic
// B-splines through their nodes, docs/CONTACT.md "Smooth surfaces": C2 contact forces, energy
// balanced on the 0.25 mm mesh), kCurved (circular arcs, "Curved surfaces": no facet bump as a
// roller turns; creates energy on rims finer than 0.35 mm) or kFaceted (node to chord).
enum class RaceContact { kFaceted, kCurved, kSmooth };
// How the rigid-roller models (hybrid, lumped) place their parts at t = 0. kSeated: each roller
// on the outer raceway, the inner ring lowered along the load onto the first roller, so the
// ramped load builds on closed contacts; kCentred: rollers on the pitch circle, ring centred (the
// load first closes the clearance and the ring strikes the rollers). docs/BEARING_MODEL.md.
enum class StartPose { kSeated, kCentred };
// The lumped model's step rule ([solver] lumped_step; docs/BEARING_MODEL.md, "The lumped model"):
// kAccurate (energy balance within 0.1 % on the paper's scenes) or kFast (every bearing on its
// two-spring limit between spall passages and a 2.3x longer step in them: about 1.8x fewer steps
// for a spalled bearing, energy balance up to 0.3 %, the outputs within the same scatter).
enum class LumpedStep { kAccurate, kFast };

// Scene-file names ("fe", "hybrid", "lumped", "auto"; "elastic", "rigid"; "faceted", "curved",
// "smooth"), and back: the Parse functions return false for any other name.
const char* FidelityName(Fidelity fidelity);
bool ParseFidelity(const std::string& name, Fidelity* fidelity);
const char* AdapterModelName(AdapterModel adapter);
bool ParseAdapterModel(const std::string& name, AdapterModel* adapter);
const char* RaceContactName(RaceContact race_contact);
bool ParseRaceContact(const std::string& name, RaceContact* race_contact);
const char* StartPoseName(StartPose start);  // "seated", "centred"
bool ParseStartPose(const std::string& name, StartPose* start);
const char* LumpedStepName(LumpedStep step);  // "accurate", "fast"
bool ParseLumpedStep(const std::string& name, LumpedStep* step);

// What a run records ([run] outputs): roller contact forces, sensor accelerations, cage speed and
// slip, roller spin and orbit, energy terms, and kField: the von Mises stress of every element of
// the stepped mesh at run.field_rate_hz (every part in the full FE, the outer ring and adapter in
// the hybrid; the lumped model has no mesh and refuses it).
enum class Output { kContactForces, kAcceleration, kCage, kRollers, kEnergy, kField };
// Scene-file names: "contact_forces", "acceleration", "cage", "rollers", "energy", "field".
const char* OutputName(Output output);
bool ParseOutput(const std::string& name, Output* output);
// Whether `outputs` (a scene's [run] outputs) holds `output`.
bool Asks(const std::vector<Output>& outputs, Output output);

// [model]: keys fidelity, adapter, race_contact, start.
struct SceneModel {
  // "auto" (the default): the cheapest rung whose measured errors meet [run.tolerance]
  // (fidelity_choice.h), resolved when the model is built.
  Fidelity fidelity = Fidelity::kAuto;
  AdapterModel adapter = AdapterModel::kElastic;
  RaceContact race_contact = RaceContact::kSmooth;
  StartPose start = StartPose::kSeated;
  // Normal damping of the contacts, fraction of each contact's critical value (the rigid
  // rollers' race contacts and the full FE's contact pairs); absent: the models' default (0.1,
  // BearingModelOptions::contact_damping_ratio and HybridOptions::contact_damping_ratio).
  std::optional<double> contact_damping;
};

struct SceneSolver {
  double time_step_safety = 0.9;       // fraction of the critical step
  int threads = 0;                     // 0: as many as OpenMP offers
  double checkpoint_interval_s = 0.0;  // 0: no checkpoints
  // Abort the run once the energy balance error exceeds this (percent of the largest energy
  // term; checked at every progress point). 0: never. A run past it is not trustworthy.
  double max_energy_error_percent = 5.0;
  LumpedStep lumped_step = LumpedStep::kAccurate;  // the lumped model's step rule
};

struct Scene {
  std::string source;  // file name (or "<string>")
  SceneGeometry geometry;
  SceneMaterials materials;
  std::vector<Defect> defects;
  SceneOperation operation;
  SceneFriction friction;
  SceneDamping damping;
  SceneMesh mesh;
  SceneModel model;
  std::vector<Sensor> sensors;
  std::vector<Output> outputs;  // [run] outputs
  SceneRun run;
  SceneSolver solver;
  std::string effective_toml;  // after overrides and defaults
};

// Reads and validates a scene file; `overrides` are "key.path=value" strings applied first
// (see ApplyOverride). Throws InputError (one line naming file, line and key).
Scene LoadScene(const std::string& path, const std::vector<std::string>& overrides = {});
// Same from TOML text; `source_name` is used in messages.
Scene ParseScene(const std::string& toml_text,
                 const std::string& source_name,
                 const std::vector<std::string>& overrides = {});

// Parses TOML text (a scene, a sweep file); a syntax error throws InputError
// "<source_name>:<line>: <what toml++ says>".
toml::table ParseToml(const std::string& toml_text, const std::string& source_name);

// Sets one key from "a.b.c=value" (array elements by index: "defects.0.width_mm=2.27"; index ==
// size appends a table). The value is parsed as a TOML value; a bare word that is not valid TOML
// is taken as a string (catalog=N205EM). When the key already exists the new value must have the
// same type (an integer may replace a float). Throws InputError naming the key.
void ApplyOverride(toml::table& table, const std::string& assignment);

// Output names accepted under [run] outputs (OutputName of every Output).
std::vector<std::string> KnownOutputs();

}  // namespace spallkit::sim
