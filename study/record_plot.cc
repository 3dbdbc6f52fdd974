#include "study/record_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/bearing.h"
#include "core/constants.h"
#include "core/error.h"
#include "core/hdf5.h"
#include "core/record_io.h"
#include "dsp/envelope.h"
#include "dsp/spectra.h"
#include "plot/plot.h"
#include "study/spectrogram_heatmap.h"

namespace spallkit::study {
namespace {

constexpr const char* kKindNames[] = {
    "time", "spectrum", "envelope", "spectrogram", "orbit", "contact", "cage"};

bool IsHdf5(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".h5" || ext == ".hdf5" || ext == ".he5";
}

std::string WithUnits(const std::string& what, const std::string& units) {
  return units.empty() ? what : what + " (" + units + ")";
}

// Sample range [first, last) of a window in seconds; throws when it holds fewer than `min`.
std::pair<size_t, size_t> Window(const RecordPlotOptions& o, double fs, size_t n, size_t min) {
  const double from = std::max(0.0, o.from_s);
  const size_t first = static_cast<size_t>(std::ceil(from * fs - 1e-9));
  size_t last = n;
  if (std::isfinite(o.to_s))
    last = std::min(n, static_cast<size_t>(std::floor(o.to_s * fs + 1e-9)) + 1);
  if (first >= last || last - first < min)
    throw InputError("plot: the time window " + std::to_string(o.from_s) + " .. " +
                     (std::isfinite(o.to_s) ? std::to_string(o.to_s) : std::string("end")) +
                     " s holds " + std::to_string(first < last ? last - first : 0) +
                     " samples (at least " + std::to_string(min) + " needed)");
  return {first, last};
}

// Dashed markers at harmonics 1..5 of the shaft rate and of each fault frequency below x_max.
std::vector<plot::Marker> FaultMarkers(const RecordPlotOptions& o, double x_max) {
  std::vector<plot::Marker> markers;
  if (o.bearing.empty() || !(o.rpm > 0)) return markers;
  const BearingFrequencies f = ComputeFrequencies(CatalogBearing(o.bearing), o.rpm / 60.0);
  const struct {
    const char* name;
    double hz;
    size_t color;
  } families[] = {{"f_r", f.shaft_hz, 7},
                  {"BPFO", f.bpfo_hz, 3},
                  {"BPFI", f.bpfi_hz, 0},
                  {"f_b", f.f_b_hz, 2},
                  {"f_c", f.cage_hz, 4}};
  for (const auto& fam : families)
    for (int k = 1; k <= 5 && k * fam.hz <= x_max; ++k) {
      plot::Marker m;
      m.x = k * fam.hz;
      m.label = std::to_string(k) + "x" + fam.name;
      m.color = plot::PaletteColor(fam.color);
      m.thin = fam.hz == f.shaft_hz || fam.hz == f.cage_hz;
      markers.push_back(m);
    }
  return markers;
}

void AddFamilyLegend(const RecordPlotOptions& o, plot::LinePlot* p) {
  if (o.bearing.empty() || !(o.rpm > 0) || p->series.empty()) return;
  const double x0 = p->series.front().x.front(), y0 = p->series.front().y.front();
  const struct {
    const char* label;
    size_t color;
  } entries[] = {{"outer race (BPFO)", 3}, {"inner race (BPFI)", 0}, {"roller (f_b)", 2}};
  for (const auto& e : entries) {
    plot::LineSeries s;  // a single point under the first point: only the legend entry shows
    s.x = {x0};
    s.y = {y0};
    s.label = e.label;
    s.color = plot::PaletteColor(e.color);
    p->series.push_back(s);
  }
}

PlottedSeries FromPlot(const plot::LinePlot& p, const std::string& x_name) {
  PlottedSeries out;
  out.x_name = x_name;
  if (p.series.empty()) return out;
  out.x = p.series.front().x;
  for (const auto& s : p.series)
    if (s.x.size() == out.x.size() && !s.label.empty()) out.columns.emplace_back(s.label, s.y);
  return out;
}

// Record kinds: time signal, spectrum, envelope spectrum, spectrogram.
PlottedSeries PlotRecord(const std::string& input,
                         const RecordPlotOptions& o,
                         const std::string& png) {
  RecordOptions ro;
  ro.channel = o.channel;
  ro.sample_rate_hz = o.sample_rate_hz;
  const Record r = ReadRecord(input, ro);
  const double fs = r.sample_rate_hz;
  const size_t min_samples = o.kind == RecordPlotKind::kTime ? 2 : 64;
  const auto [first, last] = Window(o, fs, r.samples.size(), min_samples);
  const std::vector<double> x(r.samples.begin() + first, r.samples.begin() + last);
  const std::string name = std::filesystem::path(input).filename().string() + " " + r.channel;

  if (o.kind == RecordPlotKind::kSpectrogram) {
    dsp::StftOptions so;
    so.window = 1024;
    while (so.window > 16 && static_cast<size_t>(so.window) * 8 > x.size()) so.window /= 2;
    so.hop = std::max(1, so.window / 4);
    while (x.size() / so.hop > 1200) so.hop *= 2;
    const dsp::Spectrogram sg = dsp::Stft(x, fs, so);
    plot::Heatmap h = SpectrogramHeatmap(sg, fs, first / fs, (last - first) / fs, r.units);
    h.title = "Spectrogram of " + name + " (Hann " + std::to_string(so.window) + ", hop " +
              std::to_string(so.hop) + ")";
    PlottedSeries out;
    out.x_name = "time (s)";
    std::vector<double> freq, power;
    for (int t = 0; t < sg.frames; ++t)
      for (int f = 0; f < sg.bins; ++f) {
        out.x.push_back(first / fs + sg.time_s[t]);
        freq.push_back(sg.freq_hz[f]);
        power.push_back(sg.at(t, f));
      }
    out.columns = {{"frequency (Hz)", freq}, {"power (dB)", power}};
    h.width = o.width;
    h.height = o.height;
    plot::WriteHeatmap(png, h);
    return out;
  }

  plot::LinePlot p;
  p.width = o.width;
  p.height = o.height;
  plot::LineSeries s;
  // Dark grey under coloured fault markers, else blue.
  const bool markers = !o.bearing.empty() && o.rpm > 0;
  s.color = markers ? plot::Rgb{40, 40, 40} : plot::PaletteColor(0);
  s.thickness = 1.0;
  if (o.kind == RecordPlotKind::kTime) {
    p.title = "Time signal: " + name;
    p.x_label = "time (s)";
    p.y_label = WithUnits(r.channel, r.units);
    s.label = r.channel;
    for (size_t i = 0; i < x.size(); ++i) {
      s.x.push_back((first + i) / fs);
      s.y.push_back(x[i]);
    }
    p.series.push_back(s);
    p.legend = false;
    WriteLinePlot(png, p);
    return FromPlot(p, "time (s)");
  }
  if (o.kind == RecordPlotKind::kSpectrum) {
    dsp::WelchOptions wo;
    wo.segment = 8192;
    while (wo.segment > 16 && static_cast<size_t>(wo.segment) * 4 > x.size()) wo.segment /= 2;
    const dsp::Spectrum sp = dsp::WelchPsd(x, fs, wo);
    p.title = "Power spectral density of " + name + " (Welch, Hann " + std::to_string(wo.segment) +
              ", " + std::to_string(sp.segments) + " segments)";
    p.y_label = WithUnits("PSD", SquaredUnits(r.units.empty() ? "unit" : r.units) + "/Hz");
    p.log_y = true;
    s.label = "PSD";
    s.x = sp.freq_hz;
    s.y = sp.psd;
  } else {  // envelope
    dsp::Band band{o.band_low_hz, o.band_high_hz};
    if (!std::isfinite(band.low_hz)) band = {fs / 8, 3 * fs / 8};
    dsp::EnvelopeAnalyzer analyzer(x, fs);
    double max_alpha = o.max_hz;
    if (!std::isfinite(max_alpha)) {
      max_alpha = 500.0;
      if (!o.bearing.empty() && o.rpm > 0)
        max_alpha = 5.5 * ComputeFrequencies(CatalogBearing(o.bearing), o.rpm / 60.0).f_b_hz;
    }
    dsp::EnvelopeOptions eo;
    eo.max_alpha_hz = std::min(max_alpha, band.width_hz());
    const dsp::EnvelopeSpectrum es = analyzer.Compute(band, eo);
    char title[256];
    std::snprintf(title,
                  sizeof title,
                  "Squared envelope spectrum of %s, band %.0f-%.0f Hz",
                  name.c_str(),
                  band.low_hz,
                  band.high_hz);
    p.title = title;
    p.y_label = WithUnits("SES level |FFT(SE)|/N", SquaredUnits(r.units));
    s.label = "SES";
    for (size_t i = 1; i < es.level.size(); ++i) {
      s.x.push_back(es.freq_hz[i]);
      s.y.push_back(es.level[i]);
    }
  }
  p.x_label =
      o.kind == RecordPlotKind::kEnvelope ? "cyclic frequency alpha (Hz)" : "frequency (Hz)";
  if (s.x.empty()) throw InputError("plot: " + input + ": nothing to plot in that window/band");
  p.x_min = s.x.front();
  p.x_max = std::isfinite(o.max_hz) ? std::min(o.max_hz, s.x.back()) : s.x.back();
  p.series.push_back(s);
  p.markers = FaultMarkers(o, p.x_max);
  AddFamilyLegend(o, &p);
  WriteLinePlot(png, p);
  return FromPlot(p, p.x_label);
}

// Simulation kinds: roller orbits, contact forces, cage sliding.
PlottedSeries PlotSimulation(const std::string& input,
                             const RecordPlotOptions& o,
                             const std::string& png) {
  if (!IsHdf5(input))
    throw InputError("plot: --kind " + std::string(RecordPlotKindName(o.kind)) +
                     " needs a simulation's HDF5 file (spall simulate -o run.h5), not " + input);
  const h5::File f = h5::File::OpenReadOnly(input);
  std::string dataset;
  switch (o.kind) {
    case RecordPlotKind::kOrbit:
      dataset = "/rollers/orbit_angle";
      break;
    case RecordPlotKind::kContact: {
      const std::string which = o.channel.empty() ? "roller_outer" : o.channel;
      if (which != "roller_outer" && which != "roller_inner" && which != "roller_cage")
        throw InputError("plot: --channel " + which +
                         ": expected roller_outer, roller_inner or roller_cage");
      dataset = "/contact/" + which;
      break;
    }
    default:
      dataset = "/cage/slip_ratio";
  }
  if (!f.IsDataset(dataset) || !f.IsDataset("/time"))
    throw InputError("plot: " + input + ": no " + dataset +
                     " (add its output to the scene's [run] outputs)");
  std::vector<size_t> dims;
  const std::vector<double> data = f.ReadDataset(dataset, &dims);
  const std::vector<double> time = f.ReadDataset("/time");
  const size_t n = dims.at(0), cols = dims.size() > 1 ? dims[1] : 1;
  if (n != time.size())
    throw InputError("plot: " + input + ": " + dataset + " and /time differ in length");
  const double fs =
      f.ReadDoubleAttribute(dataset, "sample_rate_hz").value_or(1.0 / (time[1] - time[0]));
  const auto [first, last] = Window(o, fs, n, 2);

  plot::LinePlot p;
  p.width = o.width;
  p.height = o.height;
  p.x_label = "time (s)";
  const std::string name = std::filesystem::path(input).filename().string();
  if (o.kind == RecordPlotKind::kOrbit) {
    p.title = "Roller orbit angle, unwrapped: " + name;
    p.y_label = "orbit angle (revolutions)";
  } else if (o.kind == RecordPlotKind::kContact) {
    p.title = "Contact force per roller, " + dataset + ": " + name;
    p.y_label = "normal force (N)";
  } else {
    p.title = "Cage sliding ratio S = (w_c - w_c,theory) / w_c,theory: " + name;
    p.y_label = "sliding ratio (%)";
  }
  // Rows with a non-finite value (the slip ratio at rest) are left out of every series.
  std::vector<size_t> rows;
  for (size_t i = first; i < last; ++i) {
    bool finite = true;
    for (size_t c = 0; c < cols; ++c) finite = finite && std::isfinite(data[i * cols + c]);
    if (finite) rows.push_back(i);
  }
  if (rows.size() < 2)
    throw InputError("plot: " + input + ": " + dataset + " has no finite values in that window");
  for (size_t c = 0; c < cols; ++c) {
    plot::LineSeries s;
    s.label = cols == 1 ? "cage" : "roller " + std::to_string(c);
    s.color = plot::PaletteColor(c);
    s.thickness = 1.2;
    double unwrap = 0, prev = 0;
    for (size_t i : rows) {
      double v = data[i * cols + c];
      if (o.kind == RecordPlotKind::kOrbit) {
        // Unwrapped, in revolutions: a steady slope is the orbital speed.
        if (i > rows.front()) {
          const double d = v - prev;
          if (d > kPi) unwrap -= 2 * kPi;
          if (d < -kPi) unwrap += 2 * kPi;
        }
        prev = v;
        v = (v + unwrap) / (2 * kPi);
      } else if (o.kind == RecordPlotKind::kCage) {
        v *= 100.0;
      }
      s.x.push_back(time[i]);
      s.y.push_back(v);
    }
    p.series.push_back(std::move(s));
  }
  p.legend = cols > 1;
  WriteLinePlot(png, p);
  return FromPlot(p, "time (s)");
}

}  // namespace

const char* RecordPlotKindName(RecordPlotKind kind) { return kKindNames[static_cast<int>(kind)]; }

RecordPlotKind ParseRecordPlotKind(const std::string& name) {
  for (int k = 0; k < 7; ++k)
    if (name == kKindNames[k]) return static_cast<RecordPlotKind>(k);
  throw InputError("plot: --kind '" + name +
                   "': expected time, spectrum, envelope, spectrogram, orbit, contact or cage");
}

bool RecordPlotOptions::Validate(std::string* error) const {
  std::string e;
  if (sample_rate_hz < 0 || !std::isfinite(sample_rate_hz))
    e = "--fs must be > 0";
  else if (!(from_s >= 0) || (std::isfinite(to_s) && !(to_s > from_s)))
    e = "the time window needs 0 <= --from-s < --to-s";
  else if (std::isfinite(band_low_hz) != std::isfinite(band_high_hz) ||
           (std::isfinite(band_low_hz) && !(0 <= band_low_hz && band_low_hz < band_high_hz)))
    e = "--band needs 0 <= low < high (Hz)";
  else if (!bearing.empty() && !(rpm > 0))
    e = "--bearing needs --rpm > 0 for the fault-frequency markers";
  else if (std::isfinite(max_hz) && !(max_hz > 0))
    e = "--max-hz must be > 0";
  if (error) *error = e;
  return e.empty();
}

PlottedSeries PlotRecordFile(const std::string& input,
                             const RecordPlotOptions& options,
                             const std::string& png_path,
                             const std::string& csv_path) {
  std::string error;
  if (!options.Validate(&error)) throw InputError("plot: " + error);
  if (!std::filesystem::exists(input)) throw InputError("plot: " + input + ": no such file");
  const bool simulation_kind = options.kind == RecordPlotKind::kOrbit ||
                               options.kind == RecordPlotKind::kContact ||
                               options.kind == RecordPlotKind::kCage;
  PlottedSeries out = simulation_kind ? PlotSimulation(input, options, png_path)
                                      : PlotRecord(input, options, png_path);
  if (!csv_path.empty()) {
    std::vector<std::pair<std::string, std::vector<double>>> columns = {{out.x_name, out.x}};
    for (const auto& c : out.columns) columns.push_back(c);
    for (auto& c : columns)  // CSV names may not hold commas
      std::replace(c.first.begin(), c.first.end(), ',', ';');
    WriteCsvRecord(csv_path, columns);
  }
  return out;
}

}  // namespace spallkit::study
