#include "study/diagnosis_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "dsp/spectra.h"
#include "plot/plot.h"
#include "study/spectrogram_heatmap.h"

namespace spallkit::study {

namespace {

using dsp::Diagnosis;
using dsp::FaultComponent;
using dsp::Kurtogram;
using dsp::Spectrogram;
using dsp::StftOptions;
using plot::Heatmap;
using plot::LinePlot;
using plot::LineSeries;
using plot::Marker;
using plot::PaletteColor;
using plot::Rgb;
using plot::WriteHeatmap;
using plot::WriteLinePlot;

Rgb FamilyColor(FaultComponent c) {
  switch (c) {
    case FaultComponent::kOuterRace:
      return PaletteColor(3);  // red
    case FaultComponent::kInnerRace:
      return PaletteColor(0);  // blue
    case FaultComponent::kRollingElement:
      return PaletteColor(2);  // green
    case FaultComponent::kCage:
      return PaletteColor(4);  // purple
  }
  return PaletteColor(7);
}

std::string SesPlot(const Diagnosis& d, const std::string& dir) {
  LinePlot p;
  char title[256];
  std::snprintf(title,
                sizeof title,
                "Squared envelope spectrum, band %.0f-%.0f Hz (kurtosis %.2f) - verdict: %s",
                d.band.low_hz,
                d.band.high_hz,
                d.band_kurtosis,
                VerdictName(d.verdict));
  p.title = title;
  p.x_label = "cyclic frequency alpha (Hz)";
  p.y_label = "SES level |FFT(SE)|/N" +
              (d.units.empty() ? std::string() : " (" + SquaredUnits(d.units) + ")");
  double x_max = 0.0;
  for (const auto& f : d.families)
    if (f.component != FaultComponent::kCage) x_max = std::max(x_max, f.MaxLineHz());
  x_max *= 1.08;
  LineSeries s;
  s.color = {40, 40, 40};
  s.thickness = 1.0;
  s.label = "SES";
  for (size_t i = 1; i < d.ses.level.size(); ++i) {
    const double f = d.ses.freq_hz[i];
    if (f > x_max) break;
    s.x.push_back(f);
    s.y.push_back(d.ses.level[i]);
  }
  p.series.push_back(s);
  // Legend entries for the families (empty series carry only the label).
  for (const auto& det : d.faults) {
    LineSeries legend;
    legend.color = FamilyColor(det.component);
    legend.label = std::string(ComponentName(det.component)) + " (" +
                   ComponentSymbol(det.component) + ")" + (det.detected ? " DETECTED" : "");
    legend.x = {s.x.front()};
    legend.y = {s.y.front()};
    legend.thickness = 2.0;
    p.series.push_back(legend);
  }
  for (const auto& det : d.faults) {
    for (const auto& l : det.lines) {
      Marker m;
      m.x = l.line.nominal_hz * det.scale;
      m.color = FamilyColor(det.component);
      m.thin = l.line.is_sideband();
      m.label = l.line.is_sideband() ? "" : l.line.label;
      p.markers.push_back(m);
    }
  }
  p.x_min = 0.0;
  p.x_max = x_max;
  const std::string path = (std::filesystem::path(dir) / "ses.png").string();
  WriteLinePlot(path, p);
  return path;
}

std::string SpectrogramPlot(const Diagnosis& d,
                            std::span<const double> signal,
                            const std::string& dir) {
  StftOptions o;
  o.window = 1024;
  while (o.window > 64 && static_cast<size_t>(o.window) * 8 > signal.size()) o.window /= 2;
  o.hop = o.window / 2;
  // Keep the image to a sensible number of frames.
  const int max_frames = 1200;
  while (static_cast<int>(signal.size() / o.hop) > max_frames) o.hop *= 2;
  const Spectrogram sg = Stft(signal, d.sample_rate_hz, o);
  Heatmap h =
      SpectrogramHeatmap(sg, d.sample_rate_hz, 0.0, signal.size() / d.sample_rate_hz, d.units);
  char title[200];
  std::snprintf(title,
                sizeof title,
                "Spectrogram (Hann %d, hop %d), diagnosis band %.0f-%.0f Hz",
                o.window,
                o.hop,
                d.band.low_hz,
                d.band.high_hz);
  h.title = title;
  const std::string path = (std::filesystem::path(dir) / "spectrogram.png").string();
  WriteHeatmap(path, h);
  return path;
}

std::string KurtogramPlot(const Diagnosis& d, const std::string& dir) {
  const Kurtogram& k = d.kurtogram;
  // Columns at the finest node resolution; each row's nodes span several columns.
  int cols = 0;
  for (const auto& row : k.kurtosis) cols = std::max<int>(cols, row.size());
  Heatmap h;
  h.rows = static_cast<int>(k.kurtosis.size());
  h.cols = cols;
  h.values.assign(static_cast<size_t>(h.rows) * cols, 0.0);
  for (int r = 0; r < h.rows; ++r) {
    const int n = static_cast<int>(k.kurtosis[r].size());
    for (int c = 0; c < cols; ++c) {
      const int node = std::min(n - 1, static_cast<int>((c + 0.5) * n / cols));
      h.values[static_cast<size_t>(r) * cols + c] = k.kurtosis[r][node];
    }
    char lab[16];
    std::snprintf(lab, sizeof lab, "%.1f", k.levels[r]);
    h.y_tick_labels.push_back(lab);
  }
  h.x_min = 0.0;
  h.x_max = 0.5 * k.sample_rate_hz;
  h.y_min = 0.0;
  h.y_max = h.rows;
  char title[256];
  std::snprintf(title,
                sizeof title,
                "Fast kurtogram: max K = %.2f at %.0f Hz (bw %.0f Hz); diagnosis band %.0f-%.0f Hz",
                k.best.kurtosis,
                k.best.center_hz,
                k.best.bandwidth_hz,
                d.band.low_hz,
                d.band.high_hz);
  h.title = title;
  h.x_label = "frequency (Hz)";
  h.y_label = "level";
  h.colorbar_label = "spectral kurtosis";
  // Frame the chosen band's cell.
  for (int r = 0; r < h.rows; ++r) {
    if (std::abs(k.levels[r] - d.band_level) > 1e-6) continue;
    h.highlight_row = r;
    h.highlight_col =
        std::clamp(static_cast<int>(d.band.center_hz() / h.x_max * cols), 0, cols - 1);
  }
  const std::string path = (std::filesystem::path(dir) / "kurtogram.png").string();
  WriteHeatmap(path, h);
  return path;
}

}  // namespace

std::vector<std::string> WriteDiagnosisPlots(const Diagnosis& diagnosis,
                                             std::span<const double> signal,
                                             const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError("--plot-dir " + dir + ": cannot create the directory (" + ec.message() + ")");
  // Every target is checked before the first is written: no partial set of figures.
  for (const char* name : {"ses.png", "spectrogram.png", "kurtogram.png"})
    CheckReplaceableOutput((std::filesystem::path(dir) / name).string());
  return {SesPlot(diagnosis, dir),
          SpectrogramPlot(diagnosis, signal, dir),
          KurtogramPlot(diagnosis, dir)};
}

}  // namespace spallkit::study
