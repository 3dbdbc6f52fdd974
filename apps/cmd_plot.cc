// spall plot: PNG plots of a record, a simulation file or a dataset folder, without a script.
//
//   spall plot RECORD_OR_H5 --kind spectrum|envelope|spectrogram|time|orbit|contact|cage
//              [--channel C] [--fs HZ] [--from-s A] [--to-s B] [--bearing N205EM --rpm R]
//              [--band LO:HI] [--max-hz F] -o out.png [--csv out.csv]
//   spall plot study DIR --x KEY --y QUANTITY [--group KEY]... [--from-s A] -o out.png [--csv]
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "apps/command.h"
#include "apps/output_paths.h"
#include "core/error.h"
#include "study/record_plot.h"
#include "study/study_plot.h"

namespace {

struct Opts {
  std::string input, kind = "spectrum", band, output = "plot.png", csv;
  spallkit::study::RecordPlotOptions plot;
  // study
  std::string dir;
  spallkit::study::StudyPlotOptions study;
  std::vector<std::string> group;
  bool one_line = false;
  std::string study_output = "study.png", study_csv;
};

void ParseBand(const std::string& text, spallkit::study::RecordPlotOptions* o) {
  if (text.empty()) return;
  double lo = 0, hi = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf:%lf%c", &lo, &hi, &tail) != 2 || !std::isfinite(lo) ||
      !std::isfinite(hi) || !(lo >= 0 && lo < hi))
    throw spallkit::InputError("plot: --band '" + text +
                               "': expected LOW:HIGH in Hz, finite, 0 <= LOW < HIGH");
  o->band_low_hz = lo;
  o->band_high_hz = hi;
}

spallkit::apps::Register reg(
    "plot",
    "PNG plot of a record or simulation (spectrum, envelope, ...) or of a dataset's trends",
    [](CLI::App& sub) {
      auto o = std::make_shared<Opts>();
      sub.add_option("input", o->input, "Record (CSV/text or HDF5) or a simulation's HDF5");
      sub.add_option(
             "--kind", o->kind, "spectrum, envelope, spectrogram, time, orbit, contact or cage")
          ->capture_default_str();
      sub.add_option("--channel",
                     o->plot.channel,
                     "Record channel (CSV column or HDF5 dataset); contact: roller_outer, "
                     "roller_inner or roller_cage");
      sub.add_option("--fs", o->plot.sample_rate_hz, "Sample rate (Hz) of a CSV without one");
      sub.add_option("--from-s", o->plot.from_s, "Start of the time window (s)");
      sub.add_option("--to-s", o->plot.to_s, "End of the time window (s)");
      sub.add_option("--bearing", o->plot.bearing, "Catalogue bearing for fault markers");
      sub.add_option("--rpm", o->plot.rpm, "Shaft speed for fault markers (rpm)");
      sub.add_option("--band", o->band, "Envelope demodulation band LOW:HIGH (Hz)");
      sub.add_option("--max-hz", o->plot.max_hz, "Upper frequency shown (spectra)");
      sub.add_option("-o,--output", o->output, "PNG file (written atomically)")
          ->capture_default_str();
      sub.add_option("--csv", o->csv, "Also write the plotted series as CSV");
      sub.add_option("--width", o->plot.width, "Image width (pixels)");
      sub.add_option("--height", o->plot.height, "Image height (pixels)");

      CLI::App* study =
          sub.add_subcommand("study", "Trends of a dataset folder, one line per group");
      study->add_option("dir", o->dir, "Dataset folder (spall dataset run --out DIR)")->required();
      study->add_option("--x", o->study.x, "Parameter or label on the x axis")->required();
      study
          ->add_option("--y",
                       o->study.y,
                       "accel_rms, accel_z_rms, accel_kurtosis, cage_slip_rms, cage_force_rms, "
                       "outer_force_max, defective_cage_force_rms, defective_rolling_percent, "
                       "defective_slides_per_cage_rev, rms:/PATH or a numeric label")
          ->required();
      study->add_option(
          "--group", o->group, "Keys that make a line (default: the other grid keys)");
      study->add_flag("--one-line", o->one_line, "Put every case in one group");
      study->add_option("--from-s", o->study.from_s, "Skip the start-up: use t >= this (s)");
      study->add_option("-o,--output", o->study_output, "PNG file")->capture_default_str();
      study->add_option("--csv", o->study_csv, "Also write the points as CSV");

      return [o, study] {
        using namespace spallkit;
        if (study->parsed()) {
          o->study.group = o->group;
          o->study.group_set = !o->group.empty() || o->one_line;
          apps::OutputPaths paths;
          paths.Add("-o", o->study_output, true);
          paths.Add("--csv", o->study_csv);
          // No output may replace a file of the dataset it reads (index, cases).
          std::error_code ec;
          for (const auto& entry : std::filesystem::directory_iterator(o->dir, ec))
            if (entry.is_regular_file(ec))
              paths.MustDifferFrom("dataset file", entry.path().string());
          paths.Check();
          const auto r = study::PlotStudy(o->dir, o->study, o->study_output, o->study_csv);
          std::printf("wrote %s (%zu points)%s%s\n",
                      o->study_output.c_str(),
                      r.x.size(),
                      o->study_csv.empty() ? "" : " and ",
                      o->study_csv.c_str());
          return 0;
        }
        if (o->input.empty())
          throw InputError("plot: give a record or simulation file (or `plot study DIR`)");
        o->plot.kind = study::ParseRecordPlotKind(o->kind);
        ParseBand(o->band, &o->plot);
        apps::OutputPaths paths;
        paths.Add("-o", o->output, true);
        paths.Add("--csv", o->csv);
        paths.MustDifferFrom("input file", o->input);
        paths.Check();
        const auto r = study::PlotRecordFile(o->input, o->plot, o->output, o->csv);
        std::printf("wrote %s (%zu points)%s%s\n",
                    o->output.c_str(),
                    r.x.size(),
                    o->csv.empty() ? "" : " and ",
                    o->csv.c_str());
        return 0;
      };
    });

}  // namespace
