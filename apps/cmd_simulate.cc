// spall simulate: runs the bearing model of a scene (fe, hybrid, lumped, or auto: the cheapest
// rung that meets [run.tolerance]) and writes the results.
//
//   spall simulate SCENE.toml [-o run.h5] [--csv accel.csv] [--set key=value]... [--resume]
//                  [--stop-after-ms T] [--quiet] [--energy-ledger]
//
// HDF5 layout: docs/BEARING_MODEL.md ("Output file"). Progress goes to stderr: on a terminal one
// line rewritten in place, elsewhere (a log file, a batch job) one line per tenth of the run. With
// [solver] checkpoint_interval_s > 0 a checkpoint RUN.h5.ckpt is written every interval; --resume
// continues from it with results identical to an uninterrupted run.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "apps/cli_guard.h"
#include "apps/command.h"
#include "apps/output_paths.h"
#include "core/error.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"

namespace {

struct Opts {
  std::string scene;
  std::string output = "run.h5";
  std::string csv;
  std::vector<std::string> sets;
  bool resume = false;
  double stop_after_ms = 0.0;
  bool stop_after_ms_given = false;
  bool quiet = false;
  bool energy_ledger = false;
};

// Everything that can be checked before the run is: a bad path or a missing output fails in a
// second, not after the simulation.
void CheckBeforeRun(const Opts& o, const spallkit::sim::Scene& scene) {
  using spallkit::InputError;
  spallkit::apps::OutputPaths paths;
  paths.Add("-o", o.output, /*required=*/true);
  paths.Add("--csv", o.csv);
  paths.MustDifferFrom("scene file", o.scene);
  paths.Check();
  const auto& outs = scene.outputs;
  if (!o.csv.empty() &&
      (std::find(outs.begin(), outs.end(), spallkit::sim::Output::kAcceleration) == outs.end() ||
       scene.sensors.empty()))
    throw InputError("--csv " + o.csv +
                     ": the scene records no accelerations (add \"acceleration\" "
                     "to run.outputs and at least one [[sensors]])");
  if (o.stop_after_ms_given && !(o.stop_after_ms > 0))
    throw InputError("--stop-after-ms must be > 0 (got " + spallkit::apps::Number(o.stop_after_ms) +
                     ")");
}

int Run(const Opts& o) {
  using namespace spallkit;
  const sim::Scene scene = sim::LoadScene(o.scene, o.sets);
  CheckBeforeRun(o, scene);
  sim::SimulationOptions so;
  so.output_path = o.output;
  so.csv_path = o.csv;
  so.resume = o.resume;
  if (o.stop_after_ms_given) so.stop_after_s = o.stop_after_ms * 1e-3;
  so.model.track_contributor_work = o.energy_ledger;
  const bool tty = ::isatty(STDERR_FILENO) && !o.quiet;
  if (!o.quiet)
    so.progress = [tty, next_tenth = 1](const sim::SimulationProgress& p) mutable {
      const double frac = p.time / p.duration;
      // Not a terminal: carriage returns would pile up in the log, so print whole lines, one per
      // tenth of the run (a resumed run starts at the tenth it had reached).
      if (!tty) {
        if (frac < next_tenth / 10.0 - 1e-9) return;
        while (next_tenth <= 10 && frac >= next_tenth / 10.0 - 1e-9) ++next_tenth;
      }
      // A resumed run's wall time counts from its checkpoint: the rate is of this process's part.
      const double done = (p.time - p.start_time) / p.duration;
      const double eta = done > 0 ? std::max(0.0, p.wall_seconds * (1.0 - frac) / done) : 0.0;
      std::fprintf(
          stderr,
          "%s  t = %8.3f / %.3f ms  %5.1f %%  steps %ld  dt %.1f ns  wall %.0f s  eta %.0f s%s",
          tty ? "\r" : "",
          p.time * 1e3,
          p.duration * 1e3,
          100 * frac,
          p.steps,
          p.time_step * 1e9,
          p.wall_seconds,
          eta,
          tty ? " " : "\n");
      std::fflush(stderr);
    };
  sim::Simulation simulation(scene, so);
  if (!o.quiet || scene.model.fidelity == sim::Fidelity::kAuto)
    std::printf("%s\n", simulation.fidelity_reason().c_str());
  if (!o.quiet) std::printf("%s\n", simulation.model().Describe().c_str());
  for (const std::string& w : simulation.model().Warnings())
    std::fprintf(stderr, "spall: warning: %s\n", w.c_str());
  std::fflush(stdout);
  const sim::SimulationSummary s = simulation.Run();
  if (tty) std::fprintf(stderr, "\n");
  std::printf("%s\n", s.BriefReport().c_str());
  if (o.energy_ledger) std::printf("%s\n", sim::solver::LedgerReport(s.ledger, 1 << 30).c_str());
  if (s.completed) {
    std::printf("wrote %s", o.output.c_str());
    if (!o.csv.empty()) std::printf(" and %s", o.csv.c_str());
    std::printf("\n");
  } else {
    std::printf("checkpoint %s.ckpt (continue with --resume)\n", o.output.c_str());
  }
  return 0;
}

spallkit::apps::Register reg(
    "simulate", "Explicit FE simulation of a bearing scene (HDF5 results)", [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      sub.add_option("scene", o->scene, "Scene file (TOML, docs/SCENE.md)")->required();
      sub.add_option("-o,--output", o->output, "HDF5 results (written atomically)")
          ->capture_default_str();
      sub.add_option(
          "--csv", o->csv, "Also write the accelerations as CSV (spall diagnose reads it)");
      sub.add_option("--set", o->sets, "Override a scene key, e.g. mesh.size_mm=1.0 (repeatable)");
      sub.add_flag("--resume", o->resume, "Continue from OUTPUT.ckpt");
      sub.add_option("--stop-after-ms",
                     o->stop_after_ms,
                     "Stop at this simulated time after writing OUTPUT.ckpt (split long runs)")
          ->each([o](const std::string&) { o->stop_after_ms_given = true; });
      sub.add_flag("--quiet", o->quiet, "No model description or progress");
      sub.add_flag("--energy-ledger",
                   o->energy_ledger,
                   "Keep an energy account per contact pair and constraint and print it "
                   "(slower; finds what breaks the energy balance)");
      return [o] { return Run(*o); };
    });

}  // namespace
