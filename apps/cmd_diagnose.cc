// spall diagnose: envelope-analysis diagnosis of one vibration record (see docs/DIAGNOSIS.md).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "apps/cli_guard.h"
#include "apps/command.h"
#include "apps/record_options.h"
#include "apps/report_output.h"
#include "core/error.h"
#include "dsp/diagnose.h"
#include "study/diagnosis_plots.h"

namespace {

struct Opts {
  spallkit::apps::RecordInputOptions input;
  spallkit::apps::ReportOutputOptions output;
  std::string plot_dir;
  bool prewhiten = false;
  double tolerance_percent = 2.0;
  int harmonics = 5;
  double false_alarm = 1e-3;
  int first_bands = 16;
  int threads = 0;
  double min_band_hz = 0.0;
};

int Run(const Opts& o) {
  using namespace spallkit;
  o.input.Check();
  o.output.Check(o.input.record);
  if (o.threads < 0 || o.threads > dsp::DiagnoseOptions::kMaxThreads)
    throw InputError("--threads must be in 0.." +
                     std::to_string(dsp::DiagnoseOptions::kMaxThreads) + " (got " +
                     std::to_string(o.threads) + ")");
  // The ranges DiagnoseOptions::IsValid checks, named by their options.
  using Limits = dsp::DiagnoseOptions;
  const double max_tolerance_percent = 100.0 * Limits::kMaxTolerance;
  if (!(o.tolerance_percent > 0 && o.tolerance_percent <= max_tolerance_percent))
    throw InputError("--tolerance-percent must be in (0, " +
                     spallkit::apps::Number(max_tolerance_percent) + "] (got " +
                     spallkit::apps::Number(o.tolerance_percent) + ")");
  if (!(o.false_alarm > 0 && o.false_alarm < 1))
    throw InputError("--false-alarm must be in (0, 1) (got " +
                     spallkit::apps::Number(o.false_alarm) + ")");
  if (o.harmonics < 1 || o.harmonics > Limits::kMaxHarmonics)
    throw InputError("--harmonics must be in 1.." + std::to_string(Limits::kMaxHarmonics) +
                     " (got " + std::to_string(o.harmonics) + ")");
  if (!(o.min_band_hz >= 0 && std::isfinite(o.min_band_hz)))
    throw InputError("--min-band-hz must be >= 0 (got " + spallkit::apps::Number(o.min_band_hz) +
                     ")");
  const BearingGeometry g = o.input.bearing.Geometry();
  const Record record = o.input.Read();

  dsp::DiagnoseOptions opt;
  opt.harmonics = o.harmonics;
  opt.tolerance = o.tolerance_percent / 100.0;
  opt.prewhiten = o.prewhiten;
  opt.false_alarm_probability = o.false_alarm;
  opt.first_bands = o.first_bands;
  opt.threads = o.threads;
  opt.min_band_low_hz = o.min_band_hz;
  opt.kurtogram_map = !o.plot_dir.empty();  // the deeper map only for the plot
  std::string error;
  if (!opt.IsValid(&error)) throw InputError(error);

  const dsp::Diagnosis d = dsp::Diagnose(record, g, o.input.ShaftHz(), opt);
  if (!o.plot_dir.empty()) study::WriteDiagnosisPlots(d, record.samples, o.plot_dir);
  std::string text = d.BriefReport();
  if (!o.plot_dir.empty()) text += "plots: " + o.plot_dir + "/{ses,spectrogram,kurtogram}.png\n";
  o.output.Emit(text, d.ToJson(2));
  return 0;
}

spallkit::apps::Register reg(
    "diagnose",
    "Envelope-analysis fault diagnosis of a vibration record (CSV or HDF5)",
    [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      o->input.Add(sub);
      o->output.Add(sub, "summary");
      sub.add_option("--plot-dir", o->plot_dir, "write ses.png, spectrogram.png, kurtogram.png");
      sub.add_flag("--prewhiten", o->prewhiten, "cepstrum pre-whitening before the analysis");
      sub.add_option("--tolerance-percent", o->tolerance_percent, "slip / speed tolerance, %")
          ->capture_default_str();
      sub.add_option("--harmonics", o->harmonics, "harmonics per fault family")
          ->capture_default_str();
      sub.add_option("--false-alarm", o->false_alarm, "false-alarm probability per record")
          ->capture_default_str();
      sub.add_option("--first-bands",
                     o->first_bands,
                     "candidate bands searched first (most impulsive); the others only when "
                     "these show no fault (0: all at once; the false-alarm design is the same)")
          ->capture_default_str();
      sub.add_option("--min-band-hz",
                     o->min_band_hz,
                     "demodulation bands start at or above this frequency, Hz (keeps a known "
                     "low-frequency source out of the band search; 0: automatic)")
          ->capture_default_str();
      sub.add_option("--threads",
                     o->threads,
                     "threads for the band search and the kurtogram (0: automatic, up to 4; at "
                     "most 64; the result is the same for any count)")
          ->capture_default_str();
      return [o] { return Run(*o); };
    });

}  // namespace
