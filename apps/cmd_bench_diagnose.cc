// spall bench diagnose DIR: the diagnosis on every record of a labelled folder, against its ground
// truth (dsp/diagnosis_benchmark.h; manifest format in docs/DIAGNOSIS.md).
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "apps/command.h"
#include "apps/progress.h"
#include "core/error.h"
#include "dsp/diagnosis_benchmark.h"

namespace {

struct Opts {
  std::string dir;
  std::string manifest;
  bool json = false;
  int threads = 0;
};

int Run(const Opts& o) {
  using namespace spallkit;
  if (!std::filesystem::is_directory(o.dir))
    throw InputError(o.dir + ": not a directory (expected a folder of records)");
  const std::string manifest =
      o.manifest.empty() ? (std::filesystem::path(o.dir) / "manifest.json").string() : o.manifest;
  if (!std::filesystem::is_regular_file(manifest))
    throw InputError(manifest + ": no manifest (give --manifest FILE)");
  dsp::DiagnoseOptions options;
  options.threads = o.threads;
  std::string error;
  if (!options.IsValid(&error)) throw InputError("--threads: " + error);
  dsp::BenchmarkResult r;
  {
    apps::TerminalProgress bar("bench diagnose", "records");
    r = dsp::RunDiagnosisBenchmark(dsp::ReadBenchmarkManifest(manifest),
                                   options,
                                   std::bind_front(&apps::TerminalProgress::Update, &bar));
  }
  std::printf("%s\n", o.json ? r.ToJson(2).c_str() : r.BriefReport().c_str());
  return 0;
}

spallkit::apps::Register reg(
    "bench diagnose",
    "Diagnose every record of a labelled folder: confusion matrix, false alarms, time per record",
    [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      sub.add_option("dir", o->dir, "folder of records")->required();
      sub.add_option("--manifest", o->manifest, "manifest (default DIR/manifest.json)");
      sub.add_flag("--json", o->json, "print one JSON object instead of the table");
      sub.add_option("--threads", o->threads, "threads per diagnosis (0: automatic, at most 64)")
          ->capture_default_str();
      return [o] { return Run(*o); };
    });

}  // namespace
