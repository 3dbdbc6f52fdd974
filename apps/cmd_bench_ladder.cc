// spall bench ladder [SCENE...] [--quick] [--trends] [--fe [--reference F | --save-reference F]]
// [--json] [--plot pareto.png] [--duration-s T] [--set key=value]...:
// runs the scenes at every rung of the fidelity ladder on one thread and prints each rung's wall
// time per simulated second and its errors against the finest rung run (study/
// fidelity_ladder.h). Default scenes: the paper's verification scene, the same bearing healthy,
// and three defective rollers (datasets/scenes/rollers-3.toml); the paper's friction (0.01 /
// 0.005) with the lubricant traction law, as the main job, on which every rung rolls the spall
// through (docs/BEARING_MODEL.md, "Spall trapping"). Rungs: lumped, hybrid 2 / 1 mm (--quick),
// plus hybrid 0.5 mm otherwise. --fe: the full-FE sub-ladder (Coulomb friction, which the full FE
// has; paper and healthy scenes, 6000 rpm, 0.02 s): the same rungs plus fe 1 / 0.5 mm (fe 1 mm
// with --quick), against the stored fe 0.25 mm runs (--reference; --save-reference makes them).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/cli_guard.h"
#include "apps/command.h"
#include "apps/output_paths.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "plot/line_plot.h"
#include "sim/bearing/scene_limits.h"
#include "study/fidelity_ladder.h"

namespace {

struct Opts {
  std::vector<std::string> scenes;
  std::vector<std::string> sets;
  bool quick = false, json = false, trends = false, fe = false;
  std::string plot;
  double duration_s = 0.15;
  bool duration_given = false;
  std::string scenes_dir = "datasets/scenes";
  std::string reference = "datasets/reference/ladder-fe-0.25mm.json";
  std::string save_reference;
};

// The full-FE sub-ladder's stored reference, read when the file is there (the ladder then says
// which rung its errors are against).
std::vector<spallkit::study::LadderRun> ReadStoredReference(const std::string& path,
                                                            double duration_s) {
  std::ifstream in(path);
  if (!in) return {};
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw spallkit::InputError(path + ": not JSON (" + e.what() + ")");
  }
  double stored_duration = 0;
  std::vector<spallkit::study::LadderRun> runs;
  try {
    runs = spallkit::study::LadderRunsFromJson(j, &stored_duration);
  } catch (const spallkit::InputError& e) {
    throw spallkit::InputError(path + ": " + e.what());
  }
  if (std::abs(stored_duration - duration_s) > 1e-9 * duration_s)
    throw spallkit::InputError(path + ": stored runs of " +
                               spallkit::apps::Number(stored_duration) + " s, the ladder runs " +
                               spallkit::apps::Number(duration_s) + " s (give --duration-s " +
                               spallkit::apps::Number(stored_duration) + ")");
  return runs;
}

int Run(const Opts& o) {
  using namespace spallkit::sim;
  using namespace spallkit::study;
  // The scene limit on simulated time (sim/bearing/scene_limits.h), and the plot's path, before
  // any rung runs.
  if (!(o.duration_s > 0 && o.duration_s <= SceneLimits{}.max_duration_s))
    throw spallkit::InputError("--duration-s must be in (0, " +
                               spallkit::apps::Number(SceneLimits{}.max_duration_s) + "] s (got " +
                               spallkit::apps::Number(o.duration_s) + ")");
  spallkit::apps::OutputPaths paths;
  paths.Add("--plot", o.plot);
  if (!o.save_reference.empty()) paths.Add("--save-reference", o.save_reference);
  paths.Check();
  LadderOptions lo;
  lo.duration_s = o.fe && !o.duration_given ? kFeLadderDuration : o.duration_s;
  std::vector<std::string> sets = o.fe ? FeLadderSceneSets() : LadderSceneSets();
  sets.insert(sets.end(), o.sets.begin(), o.sets.end());
  const std::string dir = o.scenes_dir + "/";
  if (o.trends && !o.scenes.empty())
    throw spallkit::InputError(
        "bench ladder: --trends runs the paper's width, depth and roller "
        "scenes; give no SCENE with it");
  if (o.fe && o.trends)
    throw spallkit::InputError("bench ladder: --fe and --trends are separate ladders");
  if (!o.save_reference.empty() && !o.fe)
    throw spallkit::InputError("bench ladder: --save-reference is the --fe ladder's reference");
  const std::vector<LadderTrend> trends = o.trends ? PaperTrends() : std::vector<LadderTrend>{};
  if (o.trends) {
    for (const LadderTrend& t : trends)
      for (const std::string& name : t.scenes)
        lo.scenes.emplace_back(name, LoadScene(dir + name + ".toml", sets));
  } else if (o.scenes.empty()) {
    lo.scenes.emplace_back("paper", LoadScene(dir + "paper-verification.toml", sets));
    Scene healthy = lo.scenes.back().second;
    healthy.defects.clear();
    lo.scenes.emplace_back("healthy", healthy);
    // Its 8 mm spalls are shorter than the roller: not a 2-D (full-FE) section.
    if (!o.fe) lo.scenes.emplace_back("rollers-3", LoadScene(dir + "rollers-3.toml", sets));
  } else {
    for (const std::string& path : o.scenes) lo.scenes.emplace_back(path, LoadScene(path, sets));
  }
  const auto progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  if (!o.save_reference.empty()) {
    // The reference no benchmark run affords: the full FE at 0.25 mm, stored once.
    lo.rungs = {kFeLadderReference};
    const std::vector<LadderRun> runs = RunLadderScenes(lo, progress);
    spallkit::WriteFileAtomically(o.save_reference,
                                  LadderRunsToJson(runs, lo.duration_s).dump(1) + "\n");
    std::fprintf(stderr, "wrote %s\n", o.save_reference.c_str());
    return 0;
  }
  lo.rungs = {{Fidelity::kLumped, 0.0}, {Fidelity::kHybrid, 2e-3}};
  if (!o.trends) lo.rungs.push_back({Fidelity::kHybrid, 1e-3});
  if (!o.quick && !o.trends) lo.rungs.push_back({Fidelity::kHybrid, 0.5e-3});
  if (o.fe) {
    lo.rungs.push_back({Fidelity::kFe, 1e-3});
    if (!o.quick) lo.rungs.push_back({Fidelity::kFe, 0.5e-3});
    lo.stored_reference = ReadStoredReference(o.reference, lo.duration_s);
    if (lo.stored_reference.empty())
      std::fprintf(stderr,
                   "no stored reference at %s: the errors are against the finest rung run\n",
                   o.reference.c_str());
  }
  const LadderSummary s = RunFidelityLadder(lo, progress);
  if (!o.plot.empty()) spallkit::plot::WriteLinePlot(o.plot, LadderParetoPlot(s));
  const std::vector<LadderTrendResult> trend_results = EvaluateTrends(s, trends);
  if (o.json) {
    nlohmann::json rungs = nlohmann::json::array();
    for (const LadderRungSummary& r : s.rungs)
      rungs.push_back({{"fidelity", FidelityName(r.rung.fidelity)},
                       {"mesh_mm",
                        r.rung.fidelity == Fidelity::kLumped ? nlohmann::json(nullptr)
                                                             : nlohmann::json(r.rung.mesh_m * 1e3)},
                       {"wall_s_per_simulated_s", r.wall_s_per_simulated_s},
                       {"errors",
                        {{"f_b", r.f_b},
                         {"f_c", r.f_c},
                         {"cage_slip", r.cage_slip},
                         {"roller_load", r.roller_load},
                         {"rms", r.rms},
                         {"kurtosis", r.kurtosis},
                         {"ses_correlation", r.ses_correlation},
                         {"signal_f_b", r.signal_f_b},  // NaN (null): not measured
                         {"signal_f_c", r.signal_f_c},
                         {"spall_drop", r.spall_drop},
                         {"spall_drop_vs_geometric", r.spall_drop_vs_geometric},
                         {"roller_load_vs_harris_jones", r.roller_load_vs_harris_jones}}},
                       {"max_energy_balance_error", r.max_energy_balance_error}});
    nlohmann::json j = {{"reference", s.rungs.back().rung.Label()},
                        {"duration_s", lo.duration_s},
                        {"rungs", rungs}};
    if (o.trends) {
      nlohmann::json t = nlohmann::json::array();
      for (const LadderTrendResult& r : trend_results)
        t.push_back(
            {{"trend", r.name}, {"rung", r.rung.Label()}, {"rms", r.rms}, {"holds", r.holds}});
      j["trends"] = t;
    }
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("reference: %s, %g s per run, one thread\n%s",
                s.rungs.back().rung.Label().c_str(),
                lo.duration_s,
                s.Table().c_str());
    if (o.trends) std::printf("%s", TrendTable(trend_results).c_str());
  }
  return 0;
}

spallkit::apps::Register reg(
    "bench ladder", "Fidelity ladder: run time against error for every rung", [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      sub.add_option("scenes", o->scenes, "Scene files (default: paper, healthy, rollers-3)");
      sub.add_flag("--quick", o->quick, "Lumped and hybrid 2 / 1 mm only");
      sub.add_flag("--trends",
                   o->trends,
                   "The paper's width, depth and roller-count trends of the vibration RMS on "
                   "lumped and hybrid 2 mm (datasets/scenes/width-*, depth-*, rollers-*)");
      sub.add_flag("--fe",
                   o->fe,
                   "The full-FE sub-ladder: Coulomb friction above the spall's tipping threshold "
                   "(0.15 / 0.12), 6000 rpm, 0.02 s; lumped, hybrid 2 / 1 / 0.5 mm, fe 1 / 0.5 mm "
                   "against the stored fe 0.25 mm run (--reference)");
      sub.add_option("--reference", o->reference, "The --fe ladder's stored reference (JSON)")
          ->capture_default_str();
      sub.add_option("--save-reference",
                     o->save_reference,
                     "With --fe: run the fe 0.25 mm reference and store it here (JSON)");
      sub.add_flag("--json", o->json, "Print JSON");
      sub.add_option("--plot", o->plot, "Write the error-against-time plot (PNG)");
      CLI::Option* duration =
          sub.add_option("--duration-s", o->duration_s, "Simulated time per run (--fe: 0.02)")
              ->capture_default_str();
      sub.add_option("--scenes-dir", o->scenes_dir, "Where the default scenes are")
          ->capture_default_str();
      sub.add_option("--set", o->sets, "Override a scene key in every scene (repeatable)");
      return [o, duration] {
        o->duration_given = duration->count() > 0;
        return Run(*o);
      };
    });

}  // namespace
