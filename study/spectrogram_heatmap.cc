#include "study/spectrogram_heatmap.h"

#include <algorithm>

namespace spallkit::study {

std::string SquaredUnits(const std::string& units) {
  const bool compound = units.find_first_of("/^* ") != std::string::npos;
  return (compound ? "(" + units + ")" : units) + "^2";
}

plot::Heatmap SpectrogramHeatmap(const dsp::Spectrogram& sg,
                                 double fs_hz,
                                 double t0_s,
                                 double duration_s,
                                 const std::string& units) {
  plot::Heatmap h;
  h.x_label = "time (s)";
  h.y_label = "frequency (Hz)";
  h.colorbar_label = "PSD (dB re " + SquaredUnits(units.empty() ? "unit" : units) + "/Hz)";
  h.rows = sg.bins;
  h.cols = sg.frames;
  h.values.resize(static_cast<size_t>(h.rows) * h.cols);
  double vmax = -1e300;
  for (int t = 0; t < sg.frames; ++t)
    for (int f = 0; f < sg.bins; ++f) {
      const double v = sg.at(t, f);
      h.values[static_cast<size_t>(f) * h.cols + t] = v;
      vmax = std::max(vmax, v);
    }
  h.v_max = vmax;
  h.v_min = vmax - 80.0;
  h.x_min = t0_s;
  h.x_max = t0_s + duration_s;
  h.y_min = 0.0;
  h.y_max = 0.5 * fs_hz;
  h.row0_at_top = false;
  return h;
}

}  // namespace spallkit::study
