// The fidelity ladder benchmark behind `spall bench ladder`: the same scenes run at every rung
// (lumped; hybrid at several housing meshes; full FE at several meshes) on one thread, and each
// rung's wall time per simulated second and its errors against the finest rung run and against
// independent references (pure-rolling kinematics, Harris-Jones roller load).
//
// Measured per run (after twice the speed ramp): f_c = mean cage speed / 2 pi, f_b = 2 |w_r - w_c|
// / 2 pi of the first defective roller (a healthy scene: roller 0), the cage slip ratio, the
// largest healthy-roller outer load (99th percentile over the samples of the largest
// healthy-roller load), RMS and kurtosis of the vertical acceleration, its squared envelope
// spectrum (SES; band 500 Hz to 0.45 of the output rate, cyclic frequencies up to five times the
// kinematic f_b), the energy balance. The SES error of a rung is 1 - the correlation coefficient
// of its SES with the reference's over those cyclic frequencies: 0 when the fault comb has the
// same shape, whatever the sensor's gain. f_b and f_c from the signal: `spall diagnose`'s
// measured rates of that record (dsp/diagnose.h), NaN where the diagnosis measures none (a record
// of a few cage turns, as the default 0.15 s, is too short: run the ladder with --duration-s 1).
#pragma once

#include <functional>
#include <limits>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "plot/line_plot.h"
#include "sim/bearing/bearing_model.h"
#include "sim/bearing/scene.h"

namespace spallkit::study {

using sim::Fidelity;
using sim::Scene;

inline constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

struct LadderRung {
  Fidelity fidelity = Fidelity::kLumped;
  double mesh_m = 0.0;        // housing (hybrid) or whole-model (fe) element size; lumped: unused
  std::string Label() const;  // "lumped", "hybrid 2 mm", ...
};

struct LadderRun;

struct LadderOptions {
  // Scenes by name and the scene each runs (already loaded, overrides applied).
  std::vector<std::pair<std::string, Scene>> scenes;
  // Coarse to fine; the last is the reference of the errors.
  std::vector<LadderRung> rungs;
  double duration_s = 0.15;  // simulated, every run
  // A reference no benchmark run can afford (the full FE at 0.25 mm): one stored run per scene
  // (same names, same rung, same duration), appended as the last rung instead of being run
  // (datasets/reference; LadderRunsToJson / LadderRunsFromJson).
  std::vector<LadderRun> stored_reference;
  // A ladder needs min_rungs = 2 (the last is the errors' reference; a stored reference counts
  // as one); RunLadderScenes, 1.
  bool Validate(std::string* error, size_t min_rungs = 2) const;
};

struct LadderMetrics {
  double f_b_hz = 0, f_c_hz = 0, cage_slip = 0, roller_load_n = 0, rms = 0, kurtosis = 0;
  double signal_f_b_hz = kNotMeasured, signal_f_c_hz = kNotMeasured;  // diagnosed (see above)
  double harris_jones_load_n = 0;                                     // Q_max of the same scene
  double wall_s = 0, simulated_s = 0, energy_balance_error = 0;
  std::vector<double> ses;  // SES level of the vertical acceleration, bins 1.. (see above)
  // Spall drop on the outer race (spalled scenes; 0 otherwise): mean duration of the runs of
  // samples in which the first defective roller, inside the load zone (within 40 degrees of
  // the load line), carries less than 10 % of the healthy rollers' median load there; and the
  // geometric passage time 2 asin(w / 2r) / |w_roller - w_cage| (the contact line crossing the
  // spall's chord at the simulated spin), averaged over the same samples.
  double spall_drop_s = 0, spall_drop_geometric_s = 0;
  int spall_drops = 0;  // how many runs were found
};

struct LadderRun {
  std::string scene;
  LadderRung rung;
  LadderMetrics metrics;
};

struct LadderRungSummary {
  LadderRung rung;
  double wall_s_per_simulated_s = 0;  // over all its runs
  // Largest relative error over the scenes against the finest rung (cage_slip: absolute
  // difference of the slip ratio); roller_load_vs_harris_jones against the quasi-static load.
  double f_b = 0, f_c = 0, cage_slip = 0, roller_load = 0, rms = 0, kurtosis = 0;
  // Diagnosed f_b and f_c against the reference's diagnosed ones, over the scenes where both were
  // measured; NaN where none was.
  double signal_f_b = kNotMeasured, signal_f_c = kNotMeasured;
  double ses_correlation = 0;  // 1 - correlation coefficient of the SES with the reference's
  double spall_drop = 0;       // spall-drop duration against the reference's (spalled scenes)
  double spall_drop_vs_geometric = 0;  // and against the geometric passage time
  double roller_load_vs_harris_jones = 0;
  double max_energy_balance_error = 0;
};

struct LadderSummary {
  std::vector<LadderRun> runs;
  std::vector<LadderRungSummary> rungs;
  std::string Table() const;  // one line per rung
};

// Stored runs as JSON ({"duration_s", "runs": [{"scene", "fidelity", "mesh_mm", "metrics": {...,
// "ses": [...]}}]}) and back; LadderRunsFromJson throws InputError naming the key that is missing
// or of the wrong type.
nlohmann::json LadderRunsToJson(const std::vector<LadderRun>& runs, double duration_s);
std::vector<LadderRun> LadderRunsFromJson(const nlohmann::json& j, double* duration_s);

// Runs every scene at every rung (one thread each), scene by scene. `progress` gets one line per
// finished run. Throws InputError for invalid options (one rung is enough) or scenes.
std::vector<LadderRun> RunLadderScenes(
    const LadderOptions& options, const std::function<void(const std::string&)>& progress = {});
// RunLadderScenes, then each rung's errors against the last rung. Throws InputError for invalid
// options (fewer than two rungs) or scenes.
LadderSummary RunFidelityLadder(const LadderOptions& options,
                                const std::function<void(const std::string&)>& progress = {});

// A trend of the paper's study checked on a ladder's runs: the vertical acceleration RMS over
// `scenes` (ladder scene names, in the order of the varied quantity) must grow (kIncreasing: the
// last over the first above flat_ratio, beyond what counts as flat, and no step down by more
// than kTrendStepScatter, the run-to-run scatter of one short run's RMS with where its spall
// starts, +-11 % (docs/PAPER.md)) or stay flat (kFlat: largest over smallest at most
// flat_ratio).
inline constexpr double kTrendStepScatter = 0.11;
struct LadderTrend {
  enum class Kind { kIncreasing, kFlat };
  std::string name;  // "width", "depth", "rollers"
  std::vector<std::string> scenes;
  Kind kind = Kind::kIncreasing;
};

struct LadderTrendResult {
  std::string name;
  LadderRung rung;
  std::vector<double> rms;  // per scene of the trend
  bool holds = false;
};

// The trends at every rung of `summary` (flat_ratio: kFlat's bound). Throws InputError when a
// trend names a scene the ladder did not run.
std::vector<LadderTrendResult> EvaluateTrends(const LadderSummary& summary,
                                              const std::vector<LadderTrend>& trends,
                                              double flat_ratio = 1.5);
// The same on runs of RunLadderScenes, for each of `rungs` (trend-major, as above).
std::vector<LadderTrendResult> EvaluateTrends(const std::vector<LadderRun>& runs,
                                              const std::vector<LadderRung>& rungs,
                                              const std::vector<LadderTrend>& trends,
                                              double flat_ratio = 1.5);
// One line per trend and rung: the RMS values and whether the trend holds.
std::string TrendTable(const std::vector<LadderTrendResult>& results);

// The --set overrides every ladder scene is loaded with: the main job's friction, the paper's
// coefficients with the lubricant traction law (loaded as hybrid, the law being for the
// rigid-roller rungs; each rung then sets its own fidelity).
std::vector<std::string> LadderSceneSets();
// The full-FE sub-ladder (spall bench ladder --fe): the full FE has Coulomb friction only, and at
// the paper's mu its spalled roller is trapped (docs/BEARING_MODEL.md, "Spall trapping"); these
// sets take mu 0.15 / 0.12, above the 1.38 mm spall's tipping threshold w / 4r = 0.106, at the
// width study's 6000 rpm with a 2 ms ramp, over kFeLadderDuration (the full FE at 0.5 mm costs
// about 4 s per simulated ms). Its reference is the full FE at 0.25 mm, stored once
// (datasets/reference/ladder-fe-0.25mm.json, --save-reference).
inline constexpr double kFeLadderDuration = 0.02;
inline const LadderRung kFeLadderReference = {Fidelity::kFe, 0.25e-3};
std::vector<std::string> FeLadderSceneSets();
// The paper's three trends (docs/PAPER.md): width and count up, depth flat; scene names are the
// files of datasets/scenes (width-*, depth-*, rollers-*), without ".toml".
std::vector<LadderTrend> PaperTrends();
// The Pareto view: the largest kinematic error (f_b, f_c, cage slip) against the wall time per
// simulated second, log axes, one labelled point per rung; the reference rung (no error of its
// own) is a labelled vertical line.
plot::LinePlot LadderParetoPlot(const LadderSummary& summary);

}  // namespace spallkit::study
