#include "study/fidelity_ladder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/bearing.h"
#include "core/constants.h"
#include "core/error.h"
#include "core/record.h"
#include "dsp/diagnose.h"
#include "dsp/envelope.h"
#include "dsp/statistics.h"
#include "sim/bearing/simulation.h"
#include "sim/quasistatic/harris_jones.h"

namespace spallkit::study {
namespace {

using namespace sim;

double RelativeError(double value, double reference) {
  return reference != 0.0 ? std::abs(value / reference - 1.0) : std::abs(value);
}

double HarrisJonesQmax(const Scene& scene) {
  LoadDistributionOptions o;
  o.radial_load_n = scene.operation.radial_load_n;
  o.inner_ring_speed_rad_s = scene.operation.inner_ring_speed_rad_s;
  o.roller_length_m = scene.geometry.thickness_m;
  o.diametral_clearance_m = scene.geometry.diametral_clearance_m;
  o.roller_density_kg_m3 = scene.materials.roller.density_kg_m3;
  LoadDistributionSummary s;
  SolveLoadDistribution(o, scene.geometry.bearing, &s);
  return s.IsSolutionUsable() ? s.q_max_n : 0.0;
}

void MeasureSpallDrop(const Scene& s, const Recorder& rec, double from, LadderMetrics* m) {
  const auto& t = rec.Find("/time")->data;
  const auto& outer = rec.Find("/contact/roller_outer")->data;
  const auto& orbit = rec.Find("/rollers/orbit_angle")->data;
  const auto& spin = rec.Find("/rollers/spin")->data;
  const auto& cage = rec.Find("/cage/omega")->data;
  const int z = static_cast<int>(outer.size() / std::max<size_t>(1, t.size()));
  const Defect& d = s.defects.front();
  std::vector<bool> healthy(z, true);
  for (const Defect& e : s.defects) healthy[e.roller] = false;
  auto in_zone = [&](size_t i, int j) {  // within 40 degrees of the load line (-y)
    const double psi = std::remainder(orbit[i * z + j] + 0.5 * kPi, 2 * kPi);
    return std::abs(psi) < 40.0 * kPi / 180.0;
  };
  std::vector<double> loads;
  for (size_t i = 0; i < t.size(); ++i)
    for (int j = 0; t[i] >= from && j < z; ++j)
      if (healthy[j] && in_zone(i, j)) loads.push_back(outer[i * z + j]);
  if (loads.empty()) return;
  std::nth_element(loads.begin(), loads.begin() + loads.size() / 2, loads.end());
  const double threshold = 0.1 * loads[loads.size() / 2];
  const double half_angle =
      std::asin(std::min(1.0, 0.5 * d.width_m / (0.5 * s.geometry.bearing.element_diameter_m)));
  double total = 0, geometric = 0;
  int runs = 0, run = 0, samples = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const bool low = t[i] >= from && in_zone(i, d.roller) && outer[i * z + d.roller] < threshold;
    if (low) {
      ++run;
      geometric += 2.0 * half_angle / std::max(1e-9, std::abs(spin[i * z + d.roller] - cage[i]));
      ++samples;
    } else if (run > 0) {
      total += run, ++runs, run = 0;
    }
  }
  if (runs == 0) return;
  const double dt = t.size() > 1 ? t[1] - t[0] : 0.0;
  m->spall_drops = runs;
  m->spall_drop_s = total / runs * dt;
  m->spall_drop_geometric_s = geometric / samples;
}

LadderMetrics Measure(const Scene& scene, const LadderRung& rung, double duration) {
  Scene s = scene;
  s.model.fidelity = rung.fidelity;
  if (rung.fidelity != Fidelity::kLumped) s.mesh.size_m = s.mesh.contact_size_m = rung.mesh_m;
  // The full FE meshes the spall itself: its contact zone is refined to what the spall needs
  // (width >= 1.5, depth >= 1 element) where the rung's mesh is coarser.
  if (rung.fidelity == Fidelity::kFe)
    for (const Defect& d : s.defects)
      s.mesh.contact_size_m = std::min(s.mesh.contact_size_m, std::min(d.width_m / 1.5, d.depth_m));
  s.run.duration_s = duration;
  s.solver.threads = 1;
  s.outputs = {Output::kContactForces, Output::kAcceleration, Output::kCage, Output::kRollers};
  Simulation sim(s, {});
  const SimulationSummary sum = sim.Run();
  const Recorder& rec = sim.recorder();
  const auto& t = rec.Find("/time")->data;
  const auto& cage = rec.Find("/cage/omega")->data;
  const auto& spin = rec.Find("/rollers/spin")->data;
  const auto& outer = rec.Find("/contact/roller_outer")->data;
  const int z = sim.model().num_rollers();
  const int defective = s.defects.empty() ? 0 : s.defects.front().roller;
  std::vector<bool> healthy(z, true);
  for (const Defect& d : s.defects) healthy[d.roller] = false;
  const std::vector<double>& accel = sim.recorder().Acceleration(0);
  LadderMetrics m;
  const double from = 2.0 * std::max(s.operation.ramp_s, s.operation.load_ramp_s);
  std::vector<double> peaks, x;  // x: the vertical acceleration after the ramps
  int n = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] < from) continue;
    m.f_c_hz += cage[i];
    m.f_b_hz += 2.0 * std::abs(spin[i * z + defective] - cage[i]);
    double peak = 0;
    for (int j = 0; j < z; ++j)
      if (healthy[j]) peak = std::max(peak, outer[i * z + j]);
    peaks.push_back(peak);
    if (i < accel.size()) x.push_back(accel[i]);
    ++n;
  }
  if (n == 0) throw InputError("bench ladder: duration_s leaves no samples after the ramps");
  m.f_c_hz /= 2 * kPi * n;
  m.f_b_hz /= 2 * kPi * n;
  m.cage_slip = sum.cage_slip_mean;
  std::sort(peaks.begin(), peaks.end());
  m.roller_load_n = peaks[static_cast<size_t>(0.99 * (peaks.size() - 1))];
  {
    // RMS about the mean (the sensor's offset is not vibration), kurtosis.
    const dsp::TimeStatistics ts = dsp::ComputeTimeStatistics(x);
    m.rms = std::sqrt(std::max(0.0, ts.rms * ts.rms - ts.mean * ts.mean));
    m.kurtosis = ts.kurtosis;
    // SES of the vertical acceleration after the ramps (module comment).
    const double fs = s.run.output_rate_hz;
    const double shaft_hz = s.operation.inner_ring_speed_rad_s / (2 * kPi);
    const double f_b = ComputeFrequencies(s.geometry.bearing, shaft_hz).f_b_hz;
    dsp::EnvelopeOptions eo;
    eo.max_alpha_hz = 5.0 * f_b;
    const dsp::EnvelopeSpectrum ses =
        dsp::SquaredEnvelopeSpectrum(x, fs, dsp::Band{500.0, 0.45 * fs}, eo);
    m.ses.assign(ses.level.begin() + (ses.level.empty() ? 0 : 1), ses.level.end());
    // The rates from the signal, as `spall diagnose` measures them (too short a record, or no
    // roller comb: not measured).
    try {
      Record record;
      record.samples = std::move(x);
      record.sample_rate_hz = fs;
      const dsp::Diagnosis d = dsp::Diagnose(record, s.geometry.bearing, shaft_hz);
      if (d.measured_f_b_hz) m.signal_f_b_hz = *d.measured_f_b_hz;
      if (d.measured_f_c_hz) m.signal_f_c_hz = *d.measured_f_c_hz;
    } catch (const InputError&) {
    }
  }
  if (!s.defects.empty()) MeasureSpallDrop(s, rec, from, &m);
  m.harris_jones_load_n = HarrisJonesQmax(s);
  m.wall_s = sum.wall_seconds;
  m.simulated_s = sum.time;
  m.energy_balance_error = sum.energy_balance_error;
  return m;
}

// 1 - Pearson correlation of two spectra over their common bins (1 when either is flat).
double SesCorrelationError(const std::vector<double>& a, const std::vector<double>& b) {
  const size_t n = std::min(a.size(), b.size());
  if (n < 2) return 1.0;
  double ma = 0, mb = 0;
  for (size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= n, mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  if (!(saa > 0 && sbb > 0)) return 1.0;
  return std::max(0.0, 1.0 - sab / std::sqrt(saa * sbb));
}

}  // namespace

std::string LadderRung::Label() const {
  std::ostringstream os;
  os << FidelityName(fidelity);
  if (fidelity != Fidelity::kLumped) os << " " << mesh_m * 1e3 << " mm";
  return os.str();
}

bool LadderOptions::Validate(std::string* error, size_t min_rungs) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = "bench ladder: " + m;
    return false;
  };
  if (scenes.empty()) return fail("no scenes");
  if (!stored_reference.empty()) {
    if (min_rungs > 1) --min_rungs;  // the stored reference is the last rung
    for (const auto& [name, scene] : scenes) {
      const auto it = std::find_if(stored_reference.begin(),
                                   stored_reference.end(),
                                   [&](const LadderRun& r) { return r.scene == name; });
      if (it == stored_reference.end()) return fail("the stored reference has no run of " + name);
      if (it->rung.Label() != stored_reference.front().rung.Label())
        return fail("the stored reference's runs are of different rungs");
      // Runs end on the first step at or past the duration.
      if (std::abs(it->metrics.simulated_s - duration_s) > 1e-3 * duration_s)
        return fail("the stored reference ran " + std::to_string(it->metrics.simulated_s) +
                    " s, the ladder " + std::to_string(duration_s) + " s");
    }
  }
  if (rungs.size() < min_rungs)
    return fail(min_rungs > 1 ? "needs at least two rungs (the last is the reference)"
                              : "needs a rung");
  for (const LadderRung& r : rungs) {
    if (r.fidelity == Fidelity::kAuto)
      return fail("a rung's fidelity must be fe, hybrid or lumped");
    if (r.fidelity != Fidelity::kLumped && !(r.mesh_m > 0)) return fail("mesh size must be > 0");
  }
  if (!(duration_s > 0)) return fail("duration_s must be > 0");
  return true;
}

std::vector<LadderRun> RunLadderScenes(const LadderOptions& options,
                                       const std::function<void(const std::string&)>& progress) {
  std::string err;
  if (!options.Validate(&err, 1)) throw InputError(err);
  std::vector<LadderRun> runs;
  for (const auto& [name, scene] : options.scenes)
    for (const LadderRung& rung : options.rungs) {
      runs.push_back({name, rung, Measure(scene, rung, options.duration_s)});
      if (progress) {
        const LadderMetrics& m = runs.back().metrics;
        std::ostringstream os;
        os.precision(4);
        os << name << " / " << rung.Label() << ": " << m.wall_s << " s wall, f_b " << m.f_b_hz
           << " Hz, f_c " << m.f_c_hz << " Hz, slip " << 100 * m.cage_slip << " %, Q "
           << m.roller_load_n << " N, rms " << m.rms << ", spall drops " << m.spall_drops << " of "
           << 1e3 * m.spall_drop_s << " ms (geometric " << 1e3 * m.spall_drop_geometric_s
           << " ms), energy " << 100 * m.energy_balance_error << " %";
        progress(os.str());
      }
    }
  return runs;
}

LadderSummary RunFidelityLadder(const LadderOptions& options,
                                const std::function<void(const std::string&)>& progress) {
  std::string err;
  if (!options.Validate(&err)) throw InputError(err);
  LadderSummary out;
  out.runs = RunLadderScenes(options, progress);
  std::vector<LadderRung> rungs = options.rungs;
  if (!options.stored_reference.empty()) {
    // Each scene's stored run after its own runs: the reference, the last rung.
    rungs.push_back(options.stored_reference.front().rung);
    std::vector<LadderRun> runs;
    for (size_t k = 0; k < options.scenes.size(); ++k) {
      runs.insert(runs.end(),
                  out.runs.begin() + k * options.rungs.size(),
                  out.runs.begin() + (k + 1) * options.rungs.size());
      for (const LadderRun& r : options.stored_reference)
        if (r.scene == options.scenes[k].first) {
          runs.push_back(r);
          break;
        }
    }
    out.runs = std::move(runs);
  }
  const size_t nr = rungs.size();
  for (size_t r = 0; r < nr; ++r) {
    LadderRungSummary s;
    s.rung = rungs[r];
    double wall = 0, simulated = 0;
    for (size_t k = 0; k < options.scenes.size(); ++k) {
      const LadderMetrics& m = out.runs[k * nr + r].metrics;
      const LadderMetrics& ref = out.runs[k * nr + nr - 1].metrics;
      wall += m.wall_s, simulated += m.simulated_s;
      s.f_b = std::max(s.f_b, RelativeError(m.f_b_hz, ref.f_b_hz));
      s.f_c = std::max(s.f_c, RelativeError(m.f_c_hz, ref.f_c_hz));
      s.cage_slip = std::max(s.cage_slip, std::abs(m.cage_slip - ref.cage_slip));
      s.roller_load = std::max(s.roller_load, RelativeError(m.roller_load_n, ref.roller_load_n));
      s.rms = std::max(s.rms, RelativeError(m.rms, ref.rms));
      s.kurtosis = std::max(s.kurtosis, RelativeError(m.kurtosis, ref.kurtosis));
      s.ses_correlation = std::max(s.ses_correlation, SesCorrelationError(m.ses, ref.ses));
      auto signal_error = [](double value, double reference, double* error) {
        if (std::isnan(value) || std::isnan(reference)) return;
        const double e = RelativeError(value, reference);
        *error = std::isnan(*error) ? e : std::max(*error, e);
      };
      signal_error(m.signal_f_b_hz, ref.signal_f_b_hz, &s.signal_f_b);
      signal_error(m.signal_f_c_hz, ref.signal_f_c_hz, &s.signal_f_c);
      if (m.spall_drops > 0 && ref.spall_drops > 0)
        s.spall_drop = std::max(s.spall_drop, RelativeError(m.spall_drop_s, ref.spall_drop_s));
      if (m.spall_drops > 0)
        s.spall_drop_vs_geometric = std::max(
            s.spall_drop_vs_geometric, RelativeError(m.spall_drop_s, m.spall_drop_geometric_s));
      s.roller_load_vs_harris_jones = std::max(
          s.roller_load_vs_harris_jones, RelativeError(m.roller_load_n, m.harris_jones_load_n));
      s.max_energy_balance_error = std::max(s.max_energy_balance_error, m.energy_balance_error);
    }
    s.wall_s_per_simulated_s = simulated > 0 ? wall / simulated : 0.0;
    out.rungs.push_back(s);
  }
  return out;
}

namespace {

// The stored metrics (LadderRunsToJson / LadderRunsFromJson), besides spall_drops and ses.
const std::pair<const char*, double LadderMetrics::*> kStoredMetrics[] = {
    {"f_b_hz", &LadderMetrics::f_b_hz},
    {"f_c_hz", &LadderMetrics::f_c_hz},
    {"cage_slip", &LadderMetrics::cage_slip},
    {"roller_load_n", &LadderMetrics::roller_load_n},
    {"rms", &LadderMetrics::rms},
    {"kurtosis", &LadderMetrics::kurtosis},
    {"signal_f_b_hz", &LadderMetrics::signal_f_b_hz},
    {"signal_f_c_hz", &LadderMetrics::signal_f_c_hz},
    {"harris_jones_load_n", &LadderMetrics::harris_jones_load_n},
    {"wall_s", &LadderMetrics::wall_s},
    {"simulated_s", &LadderMetrics::simulated_s},
    {"energy_balance_error", &LadderMetrics::energy_balance_error},
    {"spall_drop_s", &LadderMetrics::spall_drop_s},
    {"spall_drop_geometric_s", &LadderMetrics::spall_drop_geometric_s},
};

}  // namespace

nlohmann::json LadderRunsToJson(const std::vector<LadderRun>& runs, double duration_s) {
  nlohmann::json out = nlohmann::json::array();
  for (const LadderRun& r : runs) {
    nlohmann::json metrics = nlohmann::json::object();
    for (const auto& [key, field] : kStoredMetrics) {
      const double x = r.metrics.*field;
      metrics[key] = std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x);  // NaN: null
    }
    metrics["spall_drops"] = r.metrics.spall_drops;
    metrics["ses"] = r.metrics.ses;
    out.push_back({{"scene", r.scene},
                   {"fidelity", sim::FidelityName(r.rung.fidelity)},
                   {"mesh_mm", r.rung.mesh_m * 1e3},
                   {"metrics", metrics}});
  }
  return {{"duration_s", duration_s}, {"runs", out}};
}

std::vector<LadderRun> LadderRunsFromJson(const nlohmann::json& j, double* duration_s) {
  auto at = [](const nlohmann::json& o,
               const std::string& key,
               const std::string& where) -> const nlohmann::json& {
    if (!o.is_object() || !o.contains(key))
      throw InputError("stored ladder runs: " + where + " has no \"" + key + "\"");
    return o.at(key);
  };
  auto num = [&](const nlohmann::json& o, const std::string& key, const std::string& where) {
    const nlohmann::json& v = at(o, key, where);
    if (v.is_null()) return kNotMeasured;
    if (!v.is_number())
      throw InputError("stored ladder runs: " + where + "." + key + " must be a number");
    return v.get<double>();
  };
  if (duration_s) *duration_s = num(j, "duration_s", "the file");
  const nlohmann::json& list = at(j, "runs", "the file");
  if (!list.is_array()) throw InputError("stored ladder runs: \"runs\" must be an array");
  std::vector<LadderRun> runs;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = "runs[" + std::to_string(i) + "]";
    const nlohmann::json& o = list[i];
    LadderRun r;
    const nlohmann::json& scene = at(o, "scene", where);
    const nlohmann::json& fidelity = at(o, "fidelity", where);
    if (!scene.is_string() || !fidelity.is_string())
      throw InputError("stored ladder runs: " + where + ": scene and fidelity must be strings");
    r.scene = scene.get<std::string>();
    if (!sim::ParseFidelity(fidelity.get<std::string>(), &r.rung.fidelity) ||
        r.rung.fidelity == Fidelity::kAuto)
      throw InputError("stored ladder runs: " + where + ".fidelity must be fe, hybrid or lumped");
    r.rung.mesh_m = num(o, "mesh_mm", where) * 1e-3;
    const nlohmann::json& mj = at(o, "metrics", where);
    const std::string mw = where + ".metrics";
    LadderMetrics& m = r.metrics;
    for (const auto& [key, field] : kStoredMetrics) m.*field = num(mj, key, mw);
    m.spall_drops = static_cast<int>(num(mj, "spall_drops", mw));
    const nlohmann::json& ses = at(mj, "ses", mw);
    if (!ses.is_array()) throw InputError("stored ladder runs: " + mw + ".ses must be an array");
    for (const nlohmann::json& v : ses) {
      if (!v.is_number()) throw InputError("stored ladder runs: " + mw + ".ses must hold numbers");
      m.ses.push_back(v.get<double>());
    }
    runs.push_back(std::move(r));
  }
  return runs;
}

std::string LadderSummary::Table() const {
  std::ostringstream os;
  os.precision(3);
  os << "rung            wall s/sim s   f_b %   f_c %  slip pp  load %  rms %  kurt %  SES %  "
        "drop %  drop-geo %  load-HJ %  energy %  sig f_b %  sig f_c %\n";
  char line[256];
  for (const LadderRungSummary& r : rungs) {
    std::snprintf(line,
                  sizeof line,
                  "%-15s %12.3g %7.3f %7.3f %8.3f %7.2f %6.1f %7.1f %6.1f %7.1f %10.1f %9.2f %9.3f",
                  r.rung.Label().c_str(),
                  r.wall_s_per_simulated_s,
                  100 * r.f_b,
                  100 * r.f_c,
                  100 * r.cage_slip,
                  100 * r.roller_load,
                  100 * r.rms,
                  100 * r.kurtosis,
                  100 * r.ses_correlation,
                  100 * r.spall_drop,
                  100 * r.spall_drop_vs_geometric,
                  100 * r.roller_load_vs_harris_jones,
                  100 * r.max_energy_balance_error);
    os << line;
    for (double e : {r.signal_f_b, r.signal_f_c}) {
      if (std::isnan(e)) {
        std::snprintf(line, sizeof line, " %10s", "-");
      } else {
        std::snprintf(line, sizeof line, " %10.3f", 100 * e);
      }
      os << line;
    }
    os << "\n";
  }
  return os.str();
}

std::vector<LadderTrendResult> EvaluateTrends(const LadderSummary& summary,
                                              const std::vector<LadderTrend>& trends,
                                              double flat_ratio) {
  std::vector<LadderRung> rungs;
  for (const LadderRungSummary& r : summary.rungs) rungs.push_back(r.rung);
  return EvaluateTrends(summary.runs, rungs, trends, flat_ratio);
}

std::vector<LadderTrendResult> EvaluateTrends(const std::vector<LadderRun>& runs,
                                              const std::vector<LadderRung>& rungs,
                                              const std::vector<LadderTrend>& trends,
                                              double flat_ratio) {
  std::vector<LadderTrendResult> out;
  for (const LadderTrend& trend : trends)
    for (const LadderRung& rung : rungs) {
      LadderTrendResult r;
      r.name = trend.name;
      r.rung = rung;
      for (const std::string& scene : trend.scenes) {
        const auto run = std::find_if(runs.begin(), runs.end(), [&](const LadderRun& x) {
          return x.scene == scene && x.rung.fidelity == rung.fidelity &&
                 x.rung.mesh_m == rung.mesh_m;
        });
        if (run == runs.end())
          throw InputError("bench ladder: trend '" + trend.name + "' names scene '" + scene +
                           "', which the ladder did not run");
        r.rms.push_back(run->metrics.rms);
      }
      if (trend.kind == LadderTrend::Kind::kIncreasing) {
        r.holds =
            r.rms.size() >= 2 && r.rms.front() > 0 && r.rms.back() > flat_ratio * r.rms.front();
        for (size_t k = 1; k < r.rms.size(); ++k)
          r.holds = r.holds && r.rms[k] >= (1.0 - kTrendStepScatter) * r.rms[k - 1];
      } else {
        const auto [lo, hi] = std::minmax_element(r.rms.begin(), r.rms.end());
        r.holds = !r.rms.empty() && *lo > 0 && *hi / *lo <= flat_ratio;
      }
      out.push_back(r);
    }
  return out;
}

std::string TrendTable(const std::vector<LadderTrendResult>& results) {
  std::ostringstream os;
  os.precision(4);
  for (const LadderTrendResult& r : results) {
    os << r.name << " @ " << r.rung.Label() << ": RMS";
    for (double v : r.rms) os << " " << v;
    os << " m/s^2 -> " << (r.holds ? "holds" : "does not hold") << "\n";
  }
  return os.str();
}

std::vector<std::string> LadderSceneSets() {
  return {"model.fidelity=hybrid",
          "friction.model=ehl",
          "friction.mu_static=0.01",
          "friction.mu_dynamic=0.005"};
}

std::vector<std::string> FeLadderSceneSets() {
  return {"model.fidelity=hybrid",
          "friction.model=coulomb",
          "friction.mu_static=0.15",
          "friction.mu_dynamic=0.12",
          "operation.speed_rpm=6000",
          "operation.ramp_s=0.002"};
}

std::vector<LadderTrend> PaperTrends() {
  return {{"width", {"width-0.46", "width-1.38", "width-2.27"}, LadderTrend::Kind::kIncreasing},
          {"depth", {"depth-0.59", "depth-0.885", "depth-1.18"}, LadderTrend::Kind::kFlat},
          {"rollers", {"rollers-1", "rollers-2", "rollers-3"}, LadderTrend::Kind::kIncreasing}};
}

plot::LinePlot LadderParetoPlot(const LadderSummary& summary) {
  plot::LinePlot p;
  p.title = "Fidelity ladder: error against run time";
  p.x_label = "wall time per simulated second (s, one thread)";
  p.y_label = "largest of f_b, f_c, cage slip error (%)";
  p.log_x = p.log_y = true;
  p.legend = false;
  plot::LineSeries points;
  points.points = true;
  points.thickness = 2.5;
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = 0.0;
  for (const LadderRungSummary& r : summary.rungs) {
    const double x = r.wall_s_per_simulated_s, e = 100 * std::max({r.f_b, r.f_c, r.cage_slip});
    x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
    if (e > 0) {
      points.x.push_back(x);
      points.y.push_back(e);
      points.point_labels.push_back(r.rung.Label());
    } else {
      plot::Marker m;
      m.x = x;
      m.label = "reference: " + r.rung.Label();
      p.markers.push_back(m);
    }
  }
  p.series.push_back(points);
  // Room for the reference line and the labels right of the points.
  p.x_min = x_lo / 2;
  p.x_max = x_hi * 4;
  return p;
}

}  // namespace spallkit::study
