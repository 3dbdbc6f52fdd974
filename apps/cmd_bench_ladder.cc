// spall bench ladder [SCENE...] [--quick] [--trends] [--json] [--plot pareto.png] [--duration-s T]
// [--set key=value]...:
// runs the scenes at every rung of the fidelity ladder on one thread and prints each rung's wall
// time per simulated second and its errors against the finest rung run (study/
// fidelity_ladder.h). Default scenes: the paper's verification scene, the same bearing healthy,
// and three defective rollers (datasets/scenes/rollers-3.toml); the paper's friction (0.01 /
// 0.005) with the lubricant traction law, as the main job, on which every rung rolls the spall
// through (docs/BEARING_MODEL.md, "Spall trapping"). Rungs: lumped, hybrid 2 / 1 mm (--quick),
// plus hybrid 0.5 mm otherwise.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/cli_guard.h"
#include "apps/command.h"
#include "apps/output_paths.h"
#include "core/error.h"
#include "plot/line_plot.h"
#include "sim/bearing/scene_limits.h"
#include "study/fidelity_ladder.h"

namespace {

struct Opts {
  std::vector<std::string> scenes;
  std::vector<std::string> sets;
  bool quick = false, json = false, trends = false;
  std::string plot;
  double duration_s = 0.15;
  std::string scenes_dir = "datasets/scenes";
};

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
  paths.Check();
  LadderOptions lo;
  lo.duration_s = o.duration_s;
  std::vector<std::string> sets = LadderSceneSets();
  sets.insert(sets.end(), o.sets.begin(), o.sets.end());
  const std::string dir = o.scenes_dir + "/";
  if (o.trends && !o.scenes.empty())
    throw spallkit::InputError(
        "bench ladder: --trends runs the paper's width, depth and roller "
        "scenes; give no SCENE with it");
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
    lo.scenes.emplace_back("rollers-3", LoadScene(dir + "rollers-3.toml", sets));
  } else {
    for (const std::string& path : o.scenes) lo.scenes.emplace_back(path, LoadScene(path, sets));
  }
  lo.rungs = {{Fidelity::kLumped, 0.0}, {Fidelity::kHybrid, 2e-3}};
  if (!o.trends) lo.rungs.push_back({Fidelity::kHybrid, 1e-3});
  if (!o.quick && !o.trends) lo.rungs.push_back({Fidelity::kHybrid, 0.5e-3});
  const LadderSummary s = RunFidelityLadder(
      lo, [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
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
    nlohmann::json j = {
        {"reference", s.rungs.back().rung.Label()}, {"duration_s", o.duration_s}, {"rungs", rungs}};
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
                o.duration_s,
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
      sub.add_flag("--json", o->json, "Print JSON");
      sub.add_option("--plot", o->plot, "Write the error-against-time plot (PNG)");
      sub.add_option("--duration-s", o->duration_s, "Simulated time per run")
          ->capture_default_str();
      sub.add_option("--scenes-dir", o->scenes_dir, "Where the default scenes are")
          ->capture_default_str();
      sub.add_option("--set", o->sets, "Override a scene key in every scene (repeatable)");
      return [o] { return Run(*o); };
    });

}  // namespace
