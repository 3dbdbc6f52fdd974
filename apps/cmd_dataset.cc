// spall dataset run: runs a sweep (docs/DATASET.md) into a folder of case files and an index.
//
//   spall dataset run SWEEP.toml --out DIR [--workers N] [--shard i/n] [--retry-failed]
//                     [--dry-run] [--quiet]
//   mpirun -n P spall dataset run SWEEP.toml --out DIR     (cases spread over the ranks)
//
// Resumable: run it again after an interruption and it finishes the missing cases. Progress goes
// to stderr: on a terminal one line rewritten in place, elsewhere one line per finished case.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include "apps/command.h"
#include "apps/progress.h"
#include "core/error.h"
#include "study/dataset.h"
#include "study/mpi_world.h"
#include "study/sweep.h"

namespace {

struct Opts {
  std::string sweep, out, shard;
  int workers = 0;
  bool retry_failed = false, dry_run = false, quiet = false;
};

// "--shard i/n" -> (i, n).
std::pair<int, int> ParseShard(const std::string& text) {
  int i = -1, n = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &tail) != 2 || n < 1 || i < 0 || i >= n)
    throw spallkit::InputError("--shard '" + text + "': expected i/n with 0 <= i < n");
  return {i, n};
}

int DryRun(const spallkit::study::Sweep& sweep) {
  using namespace spallkit::study;
  std::printf("%s: %d cases, base scene %s\n",
              sweep.path.c_str(),
              sweep.num_cases(),
              sweep.base_scene.c_str());
  for (int i = 0; i < sweep.num_cases(); ++i) {
    const SweepCase c = MakeCase(sweep, i);
    CaseScene(sweep, c);  // every case must make a valid scene
    std::printf("%s", c.id.c_str());
    for (const std::string& o : CaseOverrides(sweep, c)) std::printf(" --set %s", o.c_str());
    std::printf("\n");
  }
  return 0;
}

int Run(const Opts& o, spallkit::study::MpiWorld& world) {
  using namespace spallkit;
  const study::Sweep sweep = study::LoadSweep(o.sweep);
  if (!o.shard.empty()) ParseShard(o.shard);  // checked before a dry run too
  if (o.dry_run) return world.rank() == 0 ? DryRun(sweep) : 0;
  if (o.out.empty()) throw InputError("dataset run: --out DIR is required");
  // Several processes that cannot talk to each other would all run every case.
  if (world.size() == 1 && study::MpiWorld::LauncherSize() > 1)
    throw InputError("dataset run: started by mpirun on " +
                     std::to_string(study::MpiWorld::LauncherSize()) +
                     " processes, but this spall was built without MPI; rebuild with Open MPI "
                     "(scripts/install-deps.sh) or use --shard i/n");

  study::DatasetOptions options;
  options.out_dir = o.out;
  // Under MPI one worker per rank unless asked (the ranks are the parallelism).
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  options.workers = o.workers > 0 ? o.workers : (world.size() > 1 ? 1 : cores);
  auto [shard, shards] = o.shard.empty() ? std::pair<int, int>{0, 1} : ParseShard(o.shard);
  options.part_index = shard * world.size() + world.rank();
  options.part_count = shards * world.size();
  // One process writes the index: the only one, or rank 0 once every rank has finished.
  options.write_index = world.size() == 1;
  options.retry_failed = o.retry_failed;
  const bool tty = ::isatty(STDERR_FILENO);
  const std::string who = world.size() > 1 ? "rank " + std::to_string(world.rank()) + ": " : "";
  if (!o.quiet)
    options.progress = [tty, who](const study::DatasetProgress& p) {
      std::fprintf(stderr,
                   "%s%s%d/%d cases done%s, %d running, elapsed %s, ETA %s (%s)%s",
                   tty ? "\r" : "",
                   who.c_str(),
                   p.done,
                   p.total,
                   p.failed ? (", " + std::to_string(p.failed) + " failed").c_str() : "",
                   p.running,
                   apps::FormatDuration(p.wall_seconds).c_str(),
                   apps::FormatDuration(p.eta_seconds).c_str(),
                   p.last_case.c_str(),
                   tty ? "   " : "\n");
      std::fflush(stderr);
    };
  const study::DatasetSummary s = study::RunDataset(sweep, options);
  if (tty && !o.quiet && s.ran + s.failed > 0) std::fprintf(stderr, "\n");
  if (world.size() > 1) {
    world.Barrier();  // every rank's cases are on disk
    if (world.rank() == 0) study::WriteIndex(sweep, o.out, study::ScanDataset(sweep, o.out));
    const long long ran = world.Sum(s.ran), failed = world.Sum(s.failed);
    const long long missing = world.Sum(s.pending);
    if (world.rank() == 0)
      std::printf("dataset %s: %d cases over %d ranks: %lld run now, %lld failed, %lld missing\n",
                  o.out.c_str(),
                  s.total_cases,
                  world.size(),
                  ran,
                  failed,
                  missing);
    if (failed > 0 && world.rank() == 0)
      std::fprintf(stderr,
                   "spall: %lld case(s) failed: their messages are in %s/index.csv (column error); "
                   "--retry-failed runs them again\n",
                   failed,
                   o.out.c_str());
    return failed > 0 ? 1 : 0;
  }
  std::printf("%s\n", s.BriefReport().c_str());
  if (shards > 1)
    std::printf(
        "shard %d/%d done; once all shards are, `spall dataset run` again writes the "
        "full index\n",
        shard,
        shards);
  if (s.failed > 0)
    std::fprintf(stderr,
                 "spall: %d case(s) failed: their messages are in %s/index.csv (column error); "
                 "--retry-failed runs them again\n",
                 static_cast<int>(s.failed),
                 o.out.c_str());
  return s.failed > 0 ? 1 : 0;
}

spallkit::apps::RegisterGroup group("dataset", "Parametric sweeps and synthetic datasets");

spallkit::apps::Register reg(
    "dataset run",
    "Run a sweep file into DIR (one HDF5 per case, index.csv/json; resumable; MPI-aware)",
    [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      sub.add_option("sweep", o->sweep, "Sweep file (TOML, docs/DATASET.md)")->required();
      sub.add_option("--out", o->out, "Dataset folder (created; rerun to resume)");
      sub.add_option("--workers", o->workers, "Cases run at once (default: cores; 1 under MPI)")
          ->check(CLI::Range(1, 4096));
      sub.add_option("--shard", o->shard, "Run only shard i of n (i/n, e.g. a Slurm array task)");
      sub.add_flag("--retry-failed", o->retry_failed, "Run failed cases again");
      sub.add_flag("--dry-run", o->dry_run, "List the cases and their --set overrides, run none");
      sub.add_flag("--quiet", o->quiet, "No progress lines");
      return [o] {
        spallkit::study::MpiWorld world;
        if (world.size() == 1) return Run(*o, world);
        // Under MPI an error on one rank must end all of them, not leave them in a barrier.
        try {
          return Run(*o, world);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "spall: error: rank %d: %s\n", world.rank(), e.what());
          std::fflush(stderr);
          world.Abort(2);
        }
      };
    });

}  // namespace
