#include "study/identification_plots.h"

#include <cmath>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/constants.h"
#include "core/error.h"
#include "plot/plot.h"

namespace spallkit::study {

void WriteIdentificationPlots(const identify::Identification& id, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError("--plot-dir " + dir + ": cannot create (" + ec.message() + ")");
  auto path = [&](const char* name) { return (std::filesystem::path(dir) / name).string(); };
  // Every target is checked before the first is written: no partial set of figures.
  for (const char* name : {"cage_average.png", "sidebands.png", "delay.png"})
    CheckReplaceableOutput(path(name));
  if (!id.roller_signature) return;

  if (id.cage_average.bins() > 0 && !id.count_fit.best.empty()) {
    plot::LinePlot p;
    p.title = "cage-synchronous average of the squared envelope";
    p.x_label = "cage phase (deg)";
    p.y_label = "squared envelope";
    const identify::CageAverage& a = id.cage_average;
    plot::LineSeries data, lo, hi;
    for (int i = 0; i < a.bins(); ++i) {
      const double x = a.BinCenterRad(i) * 180.0 / kPi;
      data.x.push_back(x);
      data.y.push_back(a.mean[i]);
      lo.x.push_back(x);
      lo.y.push_back(a.mean[i] - a.sigma[i]);
      hi.x.push_back(x);
      hi.y.push_back(a.mean[i] + a.sigma[i]);
    }
    data.label = "average";
    data.color = plot::PaletteColor(0);
    lo.color = hi.color = plot::Rgb{170, 190, 220};
    lo.thickness = hi.thickness = 1.0;
    lo.label = "+/- standard error";
    p.series = {lo, hi, data};
    const int k = id.count_fit.MostProbable();
    for (int show : {1, k}) {
      if (show < 1 || show >= static_cast<int>(id.count_fit.best.size())) continue;
      const identify::HumpFit& f = id.count_fit.best[show];
      if (f.model.size() != static_cast<size_t>(a.bins())) continue;
      plot::LineSeries m;
      m.x = data.x;
      m.y = f.model;
      m.label = "K = " + std::to_string(show) + " fit";
      m.color = plot::PaletteColor(show == k ? 3 : 7);
      m.thickness = 2.0;
      p.series.push_back(m);
      if (show == 1 && k == 1) break;
    }
    plot::WriteLinePlot(path("cage_average.png"), p);
  }

  const identify::SpinSidebands& sb = id.sidebands;
  if (sb.harmonics > 0) {
    plot::LinePlot p;
    p.title = "f_c sidebands of the spin harmonics (|S| / noise)";
    p.x_label = "sideband order m (line at j f_s + m f_c)";
    p.y_label = "|S| / noise rms";
    for (int j = 1; j <= sb.harmonics; ++j) {
      plot::LineSeries s;
      for (int m = -sb.orders; m <= sb.orders; ++m) {
        s.x.push_back(m);
        s.y.push_back(std::abs(sb.value[sb.Index(j, m)]) /
                      std::sqrt(sb.noise_power[sb.Index(j, m)]));
      }
      s.label =
          "j = " + std::to_string(j) + (j % 2 == 0 ? " (" + std::to_string(j / 2) + " f_b)" : "");
      s.color = plot::PaletteColor(j - 1);
      p.series.push_back(s);
    }
    plot::WriteLinePlot(path("sidebands.png"), p);
  }

  const identify::WidthFit& w = id.width_fit;
  if (w.usable && !w.best.model.empty()) {
    plot::LinePlot p;
    p.title = "load-zone autocorrelation of the squared envelope";
    p.x_label = "lag (ms)";
    p.y_label = "R";
    plot::LineSeries data, model;
    for (size_t i = 0; i < w.best.model.size(); ++i) {
      data.x.push_back(w.correlation.TauSeconds(static_cast<int>(i)) * 1e3);
      data.y.push_back(w.correlation.mean[i]);
    }
    model.x = data.x;
    model.y = w.best.model;
    data.label = "data";
    data.color = plot::PaletteColor(0);
    model.label = "entry-exit model";
    model.color = plot::PaletteColor(3);
    p.series = {data, model};
    p.markers.push_back({w.best.delay_s * 1e3, "dt", plot::PaletteColor(3), true, false});
    p.markers.push_back({w.delay_low_s * 1e3, "5 %", plot::PaletteColor(7), true, true});
    p.markers.push_back({w.delay_high_s * 1e3, "95 %", plot::PaletteColor(7), true, true});
    plot::WriteLinePlot(path("delay.png"), p);
  }
}

}  // namespace spallkit::study
