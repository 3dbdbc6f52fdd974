#include "identify/spin_sidebands.h"

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "core/error.h"
#include "dsp/fft.h"
#include "identify/line_dft.h"

namespace spallkit::identify {

SpinSidebands MeasureSpinSidebands(std::span<const double> se,
                                   double rate_hz,
                                   double spin_hz,
                                   double cage_hz,
                                   int harmonics,
                                   int orders,
                                   int spin_step,
                                   int window_bins) {
  SPALLKIT_CHECK(spin_hz > 0 && cage_hz > 0 && rate_hz > 0 && spin_step >= 1,
                 "bad sideband arguments");
  const int n = static_cast<int>(se.size()) - static_cast<int>(se.size()) % 2;
  SPALLKIT_CHECK(n >= 16, "squared envelope too short for sidebands");
  SpinSidebands out;
  out.spin_hz = spin_step * spin_hz;
  out.cage_hz = cage_hz;
  out.orders = orders;
  const double nyquist = 0.5 * rate_hz;
  out.harmonics = harmonics;
  while (out.harmonics > 0 &&
         SidebandsHighestLineHz(spin_hz, cage_hz, out.harmonics, orders, spin_step) >=
             0.95 * nyquist)
    --out.harmonics;
  if (out.harmonics == 0) return out;

  double mean = 0.0;
  for (int i = 0; i < n; ++i) mean += se[i];
  mean /= n;
  // Power spectrum of the record for the floors.
  std::vector<double> x(se.begin(), se.begin() + n);
  for (double& v : x) v -= mean;
  dsp::RealFft fft(n);
  std::vector<std::complex<double>> spec(n / 2 + 1);
  fft.Forward(x.data(), spec.data());
  const double df = rate_hz / n;
  std::vector<double> power(spec.size());
  for (size_t k = 0; k < spec.size(); ++k) power[k] = std::norm(spec[k]) / (double(n) * n);
  // Bins near any comb line (every harmonic up to J + 1, orders up to M + 2) are not floor.
  std::vector<char> masked(spec.size(), 0);
  for (int j = 0; j <= spin_step * (out.harmonics + 1); ++j)
    for (int m = -(orders + 2); m <= orders + 2; ++m) {
      const double f = j * spin_hz + m * cage_hz;
      if (f < 0) continue;
      const int c = static_cast<int>(std::lround(f / df));
      for (int b = c - 2; b <= c + 2; ++b)
        if (b >= 0 && b < static_cast<int>(masked.size())) masked[b] = 1;
    }
  out.value.resize(out.harmonics * (2 * orders + 1));
  out.noise_power.resize(out.value.size());
  for (int j = 1; j <= out.harmonics; ++j)
    for (int m = -orders; m <= orders; ++m) {
      const double f = out.FrequencyHz(j, m);
      out.value[out.Index(j, m)] = DftAt(std::span<const double>(se.data(), n), mean, rate_hz, f);
      const int c = static_cast<int>(std::lround(f / df));
      std::vector<double> w;
      for (int b = std::max(1, c - window_bins);
           b <= std::min<int>(static_cast<int>(power.size()) - 1, c + window_bins);
           ++b)
        if (!masked[b]) w.push_back(power[b]);
      double floor = 0.0;
      if (!w.empty()) {
        std::nth_element(w.begin(), w.begin() + w.size() / 2, w.end());
        floor = w[w.size() / 2] / std::log(2.0);
      }
      out.noise_power[out.Index(j, m)] = std::max(floor, 1e-300);
    }
  return out;
}

}  // namespace spallkit::identify
