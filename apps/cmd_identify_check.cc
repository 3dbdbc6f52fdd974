// spall identify-check: `spall identify` on simulated records of known truth, with noise added at
// given SNRs; prints the count confusion, width errors, interval coverage and the reliability of
// the stated probabilities (docs/IDENTIFY.md, "Validation on simulated records").
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "apps/cli_guard.h"
#include "apps/command.h"
#include "apps/identify_options.h"
#include "apps/output_paths.h"
#include "apps/progress.h"
#include "core/atomic_file.h"
#include "core/constants.h"
#include "core/error.h"
#include "identify/validation.h"

namespace {

struct Opts {
  std::vector<std::string> inputs;
  std::string channel = "/signals/accel_y";
  double from_s = 0.05;
  std::string snr = "inf";
  unsigned long long seed = 1;
  bool no_load = false;
  int workers = 1;
  std::string csv;
  double sensor_angle_deg = 0.0;
  CLI::Option* sensor_option = nullptr;
  spallkit::apps::IdentifyStatementOptions statements;
};

std::vector<double> ParseSnrList(const std::string& text) {
  std::vector<double> out;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    if (item == "inf" || item == "clean") {
      out.push_back(std::numeric_limits<double>::infinity());
    } else {
      size_t used = 0;
      double v = 0.0;
      try {
        v = std::stod(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != item.size() || item.empty() || !std::isfinite(v))
        throw spallkit::InputError("--snr-db: expected comma-separated dB values or inf (got '" +
                                   item + "')");
      out.push_back(v);
    }
    start = comma + 1;
  }
  return out;
}

int Run(const Opts& o) {
  using namespace spallkit;
  if (!(o.from_s >= 0))
    throw InputError("--from-s must be >= 0 s (got " + apps::Number(o.from_s) + ")");
  identify::ValidationOptions vo;
  vo.channel = o.channel;
  vo.skip_s = o.from_s;
  vo.snr_db = ParseSnrList(o.snr);
  vo.seed = o.seed;
  vo.give_load = !o.no_load;
  vo.workers = o.workers;
  if (o.sensor_option && o.sensor_option->count() > 0)
    vo.identify.count.sensor_angle_rad = o.sensor_angle_deg * kPi / 180.0;
  o.statements.Apply(&vo.identify);
  std::string error;
  if (!vo.IsValid(&error)) throw InputError(error);
  apps::OutputPaths paths;
  paths.Add("--csv", o.csv);
  for (const auto& in : o.inputs) paths.MustDifferFrom("input", in);
  paths.Check();
  std::vector<std::string> files;
  for (const auto& in : o.inputs) {
    if (in.size() > 3 && in.compare(in.size() - 3, 3, ".h5") == 0) {
      files.push_back(in);
    } else {
      for (auto& f : identify::CaseFiles(in)) files.push_back(f);
    }
  }
  identify::ValidationReport report;
  {
    apps::TerminalProgress bar("identify-check", "records");
    vo.progress = std::bind_front(&apps::TerminalProgress::Update, &bar);
    report = identify::ValidateOnFiles(files, vo);
  }
  if (!o.csv.empty()) WriteFileAtomically(o.csv, report.ToCsv());
  std::printf("%s", report.Summary().c_str());
  return 0;
}

spallkit::apps::Register reg(
    "identify-check",
    "spall identify on simulated records of known truth, with added noise: count and width scores",
    [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      sub.add_option("inputs", o->inputs, "dataset folders (case-*.h5) or simulation .h5 files")
          ->required();
      sub.add_option("--channel", o->channel, "HDF5 channel (default /signals/accel_y)");
      sub.add_option("--from-s", o->from_s, "start-up dropped from each record, s (default 0.05)");
      sub.add_option("--snr-db",
                     o->snr,
                     "comma-separated SNRs in the clean record's diagnosis band, dB; inf = clean "
                     "(default inf)");
      sub.add_option("--seed", o->seed, "noise seed (default 1)")
          ->check(spallkit::apps::Uint64Digits());
      o->sensor_option =
          sub.add_option("--sensor-angle-deg",
                         o->sensor_angle_deg,
                         "the channel's direction from the load line, deg (as spall identify)");
      sub.add_flag("--no-load", o->no_load, "do not give Identify the scene's radial load");
      sub.add_option("--workers",
                     o->workers,
                     "files analysed side by side, one thread each (default 1; the report is the "
                     "same for any number)")
          ->check(CLI::Range(1, 256));
      o->statements.Add(sub);
      sub.add_option("--csv", o->csv, "write one row per record and SNR there");
      return [o] { return Run(*o); };
    });

}  // namespace
