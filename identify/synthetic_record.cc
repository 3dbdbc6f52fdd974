#include "identify/synthetic_record.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <set>
#include <string>

#include "core/constants.h"
#include "core/error.h"
#include "dsp/fft.h"
#include "identify/load_zone.h"

namespace spallkit::identify {
namespace {

struct Event {
  double time_s;
  double amplitude;
  bool entry;
};

// Sum of damped sines, unit peak for gain 1 in the first mode.
struct Kernel {
  std::vector<SyntheticResonance> modes;
  double length_s = 0.0;

  double operator()(double t) const {
    if (t < 0.0 || t > length_s) return 0.0;
    double v = 0.0;
    for (const auto& m : modes) {
      const double wn = 2.0 * kPi * m.hz;
      const double wd = wn * std::sqrt(1.0 - m.damping_ratio * m.damping_ratio);
      v += m.gain * std::exp(-m.damping_ratio * wn * t) * std::sin(wd * t);
    }
    return v;
  }
};

Kernel MakeKernel(std::vector<SyntheticResonance> modes) {
  Kernel k;
  k.modes = std::move(modes);
  for (const auto& m : k.modes)
    k.length_s = std::max(k.length_s, 7.0 / (m.damping_ratio * 2.0 * kPi * m.hz));
  return k;
}

void Validate(const SyntheticRecordSpec& s) {
  s.bearing.Validate();
  auto fail = [](const std::string& m) { throw InputError("synthetic record: " + m); };
  if (!(s.shaft_hz > 0) || !(s.sample_rate_hz > 0) || !(s.duration_s > 0))
    fail("shaft_hz, sample_rate_hz and duration_s must be > 0");
  if (s.resonances.empty()) fail("at least one resonance is needed");
  for (const auto& r : s.resonances)
    if (!(r.hz > 0 && r.hz < 0.5 * s.sample_rate_hz) ||
        !(r.damping_ratio > 0 && r.damping_ratio < 1))
      fail("resonance " + std::to_string(r.hz) + " Hz: needs 0 < f < fs/2 and 0 < damping < 1");
  std::set<int> slots;
  for (const auto& r : s.rollers) {
    if (r.slot < 0 || r.slot >= s.bearing.num_elements)
      fail("roller slot " + std::to_string(r.slot) + " out of 0.." +
           std::to_string(s.bearing.num_elements - 1));
    if (!slots.insert(r.slot).second) fail("two spalls in slot " + std::to_string(r.slot));
    if (!(r.width_m > 0 && r.width_m < s.bearing.element_diameter_m))
      fail("spall width must be in (0, roller diameter)");
  }
}

}  // namespace

SyntheticRecordSpec::SyntheticRecordSpec() : bearing(CatalogBearing("N205EM")) {}

Record MakeSyntheticRecord(const SyntheticRecordSpec& s, SyntheticTruth* truth) {
  Validate(s);
  const BearingFrequencies kin = ComputeFrequencies(s.bearing, s.shaft_hz);
  const double f_c = kin.cage_hz * (1.0 + s.cage_slip);
  const double f_s = kin.roller_spin_hz * (1.0 + s.spin_slip);
  const double d = s.bearing.element_diameter_m;
  const int z = s.bearing.num_elements;
  const LoadZone zone = SolveLoadZone(
      s.bearing, s.radial_load_n, s.shaft_hz, s.diametral_clearance_m, s.roller_length_m);
  std::mt19937_64 rng(s.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);

  SyntheticTruth t;
  t.cage_hz = f_c;
  t.spin_hz = f_s;
  t.surface_speed_m_s = kPi * d * f_s;
  t.load_zone_half_angle_rad = zone.half_angle_rad;

  std::vector<Event> events;
  for (const auto& r : s.rollers) {
    const double chord_angle = 2.0 * std::asin(r.width_m / d);  // roller turn, entry to exit
    const double dt = chord_angle / (2.0 * kPi * f_s);
    t.exit_delay_s.push_back(dt);
    const double psi0 = s.roller0_angle_rad + 2.0 * kPi * r.slot / z;
    // The spin phase walks once per cage revolution, when the roller is opposite the load zone.
    double walk = 0.0;
    auto next_walk_time = [&](double after) {
      // psi(t) = psi0 + 2 pi f_c t = pi (mod 2 pi)
      const double turns = (kPi - psi0) / (2.0 * kPi);
      double k = std::ceil(after * f_c - turns);
      return (k + turns) / f_c;
    };
    double walk_at = next_walk_time(0.0);
    for (long n = static_cast<long>(std::floor(r.spin_phase_rad / kPi)) - 2;; ++n) {
      double te = (n * kPi - r.spin_phase_rad - walk) / (2.0 * kPi * f_s);
      while (te >= walk_at) {
        walk += s.spin_phase_walk_rad * gauss(rng);
        walk_at = next_walk_time(walk_at + 1e-9);
        te = (n * kPi - r.spin_phase_rad - walk) / (2.0 * kPi * f_s);
      }
      if (te - dt > s.duration_s) break;
      const double psi = psi0 + 2.0 * kPi * f_c * te;
      const double q = zone.Relative(psi);
      double a = r.gain * std::max(std::pow(q, s.load_exponent), s.unloaded_floor);
      if (n % 2 != 0) a *= s.inner_race_ratio;  // odd half-turns: spall on the inner race
      if (s.sensor_angle_rad && (n % 2 == 0 || s.inner_race_projected))
        a *= std::cos(psi - *s.sensor_angle_rad);
      const double jx = s.event_jitter_s * gauss(rng), jn = s.event_jitter_s * gauss(rng);
      events.push_back({te + jx, a, false});
      events.push_back({te - dt + jn, a * s.entry_ratio, true});
    }
  }

  const Kernel exit_kernel = MakeKernel(s.resonances);
  const Kernel entry_kernel = s.entry_resonance_hz > 0
                                  ? MakeKernel({{s.entry_resonance_hz, s.entry_damping_ratio, 1.0}})
                                  : exit_kernel;
  const int n = static_cast<int>(std::lround(s.duration_s * s.sample_rate_hz));
  std::vector<double> x(n, 0.0);
  for (const auto& e : events) {
    const Kernel& k = e.entry ? entry_kernel : exit_kernel;
    const int i0 = std::max(0, static_cast<int>(std::ceil(e.time_s * s.sample_rate_hz)));
    const int i1 = std::min(n - 1, static_cast<int>((e.time_s + k.length_s) * s.sample_rate_hz));
    for (int i = i0; i <= i1; ++i) x[i] += e.amplitude * k(i / s.sample_rate_hz - e.time_s);
  }

  if (std::isfinite(s.snr_db)) {
    dsp::Band band = s.snr_band;
    if (!(band.high_hz > band.low_hz))
      band = {0.75 * s.resonances.front().hz, 1.25 * s.resonances.front().hz};
    // Signal power in the band from its spectrum; white noise puts sigma^2 (2 B / fs) there.
    const int m = n - n % 2;
    dsp::RealFft fft(m);
    std::vector<std::complex<double>> spec(m / 2 + 1);
    fft.Forward(x.data(), spec.data());
    double p = 0.0;
    for (int k = 1; k < m / 2; ++k) {
      const double f = k * s.sample_rate_hz / m;
      if (f >= band.low_hz && f <= band.high_hz) p += 2.0 * std::norm(spec[k]) / (double(m) * m);
    }
    const double band_fraction = 2.0 * band.width_hz() / s.sample_rate_hz;
    const double sigma = std::sqrt(p / std::pow(10.0, s.snr_db / 10.0) / band_fraction);
    for (double& v : x) v += sigma * gauss(rng);
    t.noise_rms = sigma;
  }

  if (truth) *truth = t;
  Record rec;
  rec.samples = std::move(x);
  rec.sample_rate_hz = s.sample_rate_hz;
  rec.channel = "synthetic";
  rec.units = "m/s^2";
  rec.source = "synthetic";
  return rec;
}

}  // namespace spallkit::identify
