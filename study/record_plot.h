// Plots of one record or one simulation file (`spall plot`): time signal, spectrum, squared
// envelope spectrum, spectrogram, and a simulation's roller orbits, contact forces and cage
// sliding. PNG through plot/, the plotted series optionally as CSV for other tools.
//
//   study::RecordPlotOptions options;
//   options.kind = study::RecordPlotKind::kEnvelope;
//   options.bearing = "N205EM";
//   options.rpm = 1200;
//   study::PlotRecordFile("run.h5", options, "ses.png", "ses.csv");
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace spallkit::study {

enum class RecordPlotKind { kTime, kSpectrum, kEnvelope, kSpectrogram, kOrbit, kContact, kCage };

// "time", "spectrum", "envelope", "spectrogram", "orbit", "contact", "cage".
const char* RecordPlotKindName(RecordPlotKind kind);
// Throws InputError listing the known kinds.
RecordPlotKind ParseRecordPlotKind(const std::string& name);

struct RecordPlotOptions {
  static constexpr double kAuto = std::numeric_limits<double>::quiet_NaN();

  RecordPlotKind kind = RecordPlotKind::kSpectrum;
  // time/spectrum/envelope/spectrogram: the record channel (CSV column or HDF5 dataset, as
  // `spall diagnose --channel`); contact: "roller_outer" (default), "roller_inner" or
  // "roller_cage".
  std::string channel;
  double sample_rate_hz = 0;        // CSV without a time column or "# fs=" comment
  double from_s = 0, to_s = kAuto;  // time window (whole record by default)
  // Fault-frequency markers (spectrum, envelope): a catalogue bearing and the shaft speed.
  std::string bearing;
  double rpm = 0;
  // Envelope: demodulation band in Hz; NaN: [fs/8, 3 fs/8] (a resonance band away from the
  // shaft harmonics; give the band the diagnosis chose for the best picture).
  double band_low_hz = kAuto, band_high_hz = kAuto;
  double max_hz = kAuto;  // upper x limit of spectra (envelope: 5 f_b or 500 Hz by default)
  int width = 1600, height = 800;

  bool Validate(std::string* error) const;
};

// What was plotted (also written as CSV when asked): the x column and one column per series.
struct PlottedSeries {
  std::string x_name;
  std::vector<double> x;
  std::vector<std::pair<std::string, std::vector<double>>> columns;
};

// Reads `input` (CSV/text record or HDF5 simulation output), draws the plot to `png_path`
// (atomically) and, when csv_path is not empty, the series to CSV. Throws InputError with one
// line for a missing file, an unknown kind, a kind the file cannot give (orbit/contact/cage
// need a simulation's HDF5), an empty time window or bad options.
PlottedSeries PlotRecordFile(const std::string& input,
                             const RecordPlotOptions& options,
                             const std::string& png_path,
                             const std::string& csv_path = "");

}  // namespace spallkit::study
