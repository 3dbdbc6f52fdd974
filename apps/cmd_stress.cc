// spall stress [--scenes N] [--seed S] [--fidelity hybrid|lumped|fe] [--max-duration-ms T]
//              [--min-mesh-mm H] [--json]: numerical stability stress test of the simulator
// (sim/stress/stress.h, docs/RELIABILITY.md). Prints one row per scene and every failure with the
// --set list that reproduces it; exit code 1 when any scene failed.
#include <cstdio>
#include <memory>
#include <string>

#include "apps/cli_guard.h"
#include "apps/command.h"
#include "core/error.h"
#include "sim/stress/stress.h"

namespace {

struct Opts {
  spallkit::sim::stress::StressOptions stress;
  std::string fidelity = "hybrid";
  double max_duration_ms = 20.0;
  bool json = false;
};

int Run(Opts& o) {
  using namespace spallkit::sim::stress;
  o.stress.max_duration_s = o.max_duration_ms * 1e-3;
  // The options by their command-line names (StressOptions::Validate names its fields).
  auto check = [](bool ok, const char* what) {
    if (!ok) throw spallkit::InputError(std::string("stress: ") + what);
  };
  check(o.stress.scenes >= 1 && o.stress.scenes <= 100000, "--scenes must be in [1, 100000]");
  check(o.max_duration_ms >= 1.0 && o.max_duration_ms <= 1000.0,
        "--max-duration-ms must be in [1, 1000]");
  check(o.stress.min_mesh_size_mm >= 0.25 && o.stress.min_mesh_size_mm <= 5.0,
        "--min-mesh-mm must be in [0.25, 5]");
  check(o.stress.max_mesh_size_mm >= 0.25 && o.stress.max_mesh_size_mm <= 5.0,
        "--max-mesh-mm must be in [0.25, 5]");
  check(o.stress.min_mesh_size_mm <= o.stress.max_mesh_size_mm,
        "--min-mesh-mm must not exceed --max-mesh-mm");
  if (!spallkit::sim::ParseFidelity(o.fidelity, &o.stress.fidelity))
    throw spallkit::InputError("stress: fidelity must be \"hybrid\", \"lumped\" or \"fe\" (got \"" +
                               o.fidelity + "\")");
  std::string error;
  if (!o.stress.Validate(&error)) throw spallkit::InputError(error);
  if (!o.json)
    o.stress.progress = [](const StressCase& c) {
      std::fprintf(stderr,
                   "scene %4d  %-8s  %6.2f s  %s\n",
                   c.index,
                   StressOutcomeName(c.outcome),
                   c.wall_seconds,
                   c.reason.substr(0, 120).c_str());
    };
  const StressSummary s = RunStress(o.stress);
  if (o.json) {
    std::printf("%s\n", s.ToJson().c_str());
  } else {
    std::printf("%s", s.Table().c_str());
    std::printf("%s\n", s.BriefReport().c_str());
  }
  return s.failed == 0 ? 0 : 1;
}

spallkit::apps::Register reg(
    "stress",
    "Numerical stability stress test: random scenes across and beyond the ranges",
    [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      sub.add_option("--scenes", o->stress.scenes, "Number of scenes")->capture_default_str();
      sub.add_option("--seed", o->stress.seed, "Seed of the draw (same scenes on every machine)")
          ->check(spallkit::apps::Uint64Digits())
          ->capture_default_str();
      sub.add_option("--fidelity", o->fidelity, "Model of every scene: hybrid, lumped or fe")
          ->capture_default_str();
      sub.add_option("--max-duration-ms", o->max_duration_ms, "Longest simulated time per scene")
          ->capture_default_str();
      sub.add_option("--min-mesh-mm", o->stress.min_mesh_size_mm, "Finest mesh size drawn")
          ->capture_default_str();
      sub.add_option("--max-mesh-mm", o->stress.max_mesh_size_mm, "Coarsest mesh size drawn")
          ->capture_default_str();
      sub.add_flag("--json", o->json, "Print one JSON object");
      return [o] { return Run(*o); };
    });

}  // namespace
