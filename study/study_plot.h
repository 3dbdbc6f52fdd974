// Trend plots of a dataset folder (`spall plot study DIR --x KEY --y QUANTITY`): one line per
// group of cases, a quantity of each case against a parameter or label.
//
// x: any parameter or numeric label of DIR/index.json ("defects.0.width_mm", "width_mm",
// "speed_rpm", ...). y: a numeric label, or a quantity computed from each case file over the
// time window [from_s, end]:
//   accel_rms        RMS of /signals/accel_y (mean removed), m/s^2
//   accel_z_rms      RMS of /signals/accel_z (mean removed), m/s^2
//   accel_kurtosis   kurtosis of /signals/accel_y (3 for a Gaussian signal)
//   cage_slip_rms    RMS of /cage/slip_ratio, in percent
//   cage_force_rms   RMS over all rollers of /contact/roller_cage, N
//   outer_force_max  largest roller-outer race force, N
//   defective_cage_force_rms       RMS of /contact/roller_cage over the defective rollers, N
//   defective_rolling_percent      time the defective rollers roll, %
//   defective_slides_per_cage_rev  their sliding episodes per cage revolution
//     (sim/bearing/roller_sliding.h; the defective rollers are the case's [[defects]] rollers,
//     the sliding measures are averaged over them; healthy cases have no value)
//   rms:/PATH        RMS of any dataset (mean kept)
// Groups: the cases with equal values of the `group` keys (default: every other [grid] key);
// cases of one group with equal x (random draws, starts) are averaged into one point, drawn with
// a bar of +/- their sample standard deviation.
#pragma once

#include <string>
#include <vector>

#include "study/record_plot.h"

namespace spallkit::study {

struct StudyPlotOptions {
  std::string x, y;
  std::vector<std::string> group;  // empty: every other grid parameter
  bool group_set = false;          // true: use `group` as given, even empty (one line)
  double from_s = 0;               // skip the start-up (speed and load ramps)
  int width = 1600, height = 800;
};

// Names of the computed quantities (for messages and --help).
std::vector<std::string> StudyQuantities();

// Reads DIR/index.json and the case files (status ok only), plots to `png_path` and, when
// csv_path is not empty, writes one row per point (group, x, y, cases averaged, their sample
// standard deviation: 0 for one case). Throws InputError for a folder without an index, an
// unknown x or y, or no numeric point.
PlottedSeries PlotStudy(const std::string& dir,
                        const StudyPlotOptions& options,
                        const std::string& png_path,
                        const std::string& csv_path = "");

}  // namespace spallkit::study
