// spall identify: number, cage positions and width of spalled rollers from a vibration record
// (docs/IDENTIFY.md). Diagnoses the record first (docs/DIAGNOSIS.md), then identifies from that.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "apps/cli_guard.h"
#include "apps/command.h"
#include "apps/identify_options.h"
#include "apps/record_options.h"
#include "apps/report_output.h"
#include "core/constants.h"
#include "core/error.h"
#include "core/format.h"
#include "dsp/diagnose.h"
#include "identify/identify.h"
#include "study/identification_plots.h"

namespace {

struct Opts {
  spallkit::apps::RecordInputOptions input;
  double load_n = 0.0;
  CLI::Option* load_option = nullptr;
  spallkit::apps::ReportOutputOptions output;
  std::string plot_dir;
  int max_count = -1;
  spallkit::apps::IdentifyStatementOptions statements;
  double sensor_angle_deg = 0.0;
  CLI::Option* sensor_option = nullptr;
};

int Run(const Opts& o) {
  using namespace spallkit;
  o.input.Check();
  o.output.Check(o.input.record);
  if (o.load_option && o.load_option->count() > 0 &&
      (!(o.load_n > 0.0) || !std::isfinite(o.load_n)))
    throw InputError("--load-n must be > 0 N (got " + std::to_string(o.load_n) + ")");
  if (o.sensor_option && o.sensor_option->count() > 0 && !(std::abs(o.sensor_angle_deg) <= 180.0))
    throw InputError("--sensor-angle-deg must be in [-180, 180] (got " +
                     spallkit::apps::Number(o.sensor_angle_deg) + ")");
  if (o.max_count != -1 && o.max_count < 1)
    throw InputError("--max-count must be >= 1 (got " + std::to_string(o.max_count) + ")");
  identify::IdentifyOptions io;  // checked before the record is read: an option error comes first
  if (o.load_option && o.load_option->count() > 0) io.radial_load_n = o.load_n;
  if (o.max_count >= 0) io.count.max_count = o.max_count;
  o.statements.Apply(&io);
  if (o.sensor_option && o.sensor_option->count() > 0)
    io.count.sensor_angle_rad = o.sensor_angle_deg * kPi / 180.0;
  std::string error;
  if (!io.IsValid(&error)) throw InputError(error);
  const BearingGeometry g = o.input.bearing.Geometry();
  const Record record = o.input.Read();
  dsp::DiagnoseOptions dopt;
  dopt.kurtogram_map = !o.plot_dir.empty();
  const dsp::Diagnosis d = dsp::Diagnose(record, g, o.input.ShaftHz(), dopt);
  const identify::Identification id = identify::Identify(record, g, o.input.ShaftHz(), d, io);
  if (!o.plot_dir.empty()) study::WriteIdentificationPlots(id, o.plot_dir);
  std::string text = "record: " + record.source + " (" + std::to_string(record.samples.size()) +
                     " samples, " + FormatNumber("%g", record.sample_rate_hz) + " Hz)\n" +
                     id.BriefReport();
  if (!o.plot_dir.empty()) text += "plots: " + o.plot_dir + "/{cage_average,sidebands,delay}.png\n";
  o.output.Emit(text, id.ToJson(2));
  return 0;
}

spallkit::apps::Register reg(
    "identify",
    "Number, cage positions and width of spalled rollers from a vibration record",
    [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      o->input.Add(sub);
      o->load_option = sub.add_option(
          "--load-n",
          o->load_n,
          "radial load, N (fixes the load zone, else it is fitted; the width needs it)");
      sub.add_option("--max-count",
                     o->max_count,
                     "largest number of defective rollers tried (default: every roller)");
      o->statements.Add(sub);
      o->sensor_option = sub.add_option(
          "--sensor-angle-deg",
          o->sensor_angle_deg,
          "sensor direction from the load line, deg (0: on it; 90: horizontal under a "
          "vertical load)");
      o->output.Add(sub, "report");
      sub.add_option(
          "--plot-dir", o->plot_dir, "write cage_average.png, sidebands.png, delay.png there");
      return [o] { return Run(*o); };
    });

}  // namespace
