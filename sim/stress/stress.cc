#include "sim/stress/stress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>

#include "core/error.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"

namespace spallkit::sim::stress {
namespace {

// A small generator with the same sequence on every platform (the standard distributions are not
// specified bit for bit): SplitMix64.
class Draw {
 public:
  Draw(std::uint64_t seed, int index)
      : state_(seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(index) + 1) {}
  std::uint64_t Next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double Uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(Next() >> 11) * 0x1.0p-53;
  }
  double LogUniform(double lo, double hi) { return std::exp(Uniform(std::log(lo), std::log(hi))); }
  bool Chance(double p) { return Uniform(0.0, 1.0) < p; }
  int Integer(int lo, int hi) {  // inclusive
    return lo + static_cast<int>(Next() % static_cast<std::uint64_t>(hi - lo + 1));
  }

 private:
  std::uint64_t state_;
};

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  std::string s = buf;
  // TOML floats need a '.' or an exponent ("20000" would be an integer, which is also accepted).
  return s;
}

// N205EM roller radius (mm): the draw ranges of the spall follow the paper's bearing.
constexpr double kRollerRadiusMm = 3.25;
constexpr int kRollers = 13;

// Sets (or replaces) one key of the case.
void Set(StressCase* c, const std::string& key, const std::string& value) {
  const std::string prefix = key + "=";
  for (auto& o : c->overrides)
    if (o.rfind(prefix, 0) == 0) {
      o = prefix + value;
      return;
    }
  c->overrides.push_back(prefix + value);
}

// One key beyond its documented range: most are rejected by the scene's checks; those the scene
// accepts must still run cleanly.
void DrawBeyond(Draw& d, StressCase* c) {
  switch (d.Integer(0, 9)) {
    case 0:
      Set(c, "operation.radial_load_n", Num(d.Uniform(6e4, 5e5)));
      break;
    case 1:
      Set(c, "operation.radial_load_n", Num(-d.Uniform(1.0, 1e4)));
      break;
    case 2:
      Set(c, "operation.speed_rpm", Num(d.Uniform(2.5e4, 2e5)));
      break;
    case 3:
      Set(c, "bearing.diametral_clearance_mm", Num(d.Uniform(0.15, 2.0)));
      break;
    case 4:
      Set(c, "defects.0.width_mm", Num(d.Uniform(3.0, 8.0)));
      break;
    case 5:
      Set(c, "defects.0.depth_mm", Num(d.Uniform(0.5, 1.5) * kRollerRadiusMm));
      break;
    case 6:
      Set(c, "friction.mu_static", Num(d.Uniform(0.5, 3.0)));
      break;
    case 7:
      Set(c, "damping.ratio", Num(d.Uniform(0.3, 2.0)));
      break;
    case 8:
      Set(c, "mesh.size_mm", Num(d.Uniform(6.0, 20.0)));
      break;
    default:
      Set(c, "run.duration_s", d.Chance(0.5) ? "0.0" : Num(d.Uniform(100.0, 1e6)));
      break;
  }
}

struct RunChecks {
  double max_overlap_fraction = 0.0;
};

// Worst roller-race overlap beyond each roller's spall depth, as a fraction of the roller radius.
double WorstOverlap(const BearingModel& model) {
  const BearingMesh& m = model.bearing_mesh();
  const BodyMotion inner = model.InnerRingMotion();
  // Against the outer raceway where it is now: the housing lets the whole ring move (the elastic
  // adapter carries it sideways at tens of N/um), which is not an overlap.
  const BodyMotion outer = model.OuterRingMotion();
  std::vector<double> depth(model.num_rollers(), 0.0);
  for (const Defect& d : model.scene().defects)
    if (d.roller < model.num_rollers()) depth[d.roller] = d.depth_m;
  double worst = 0.0;
  for (int j = 0; j < model.num_rollers(); ++j) {
    const BodyMotion r = model.RollerMotion(j);
    const double d_inner = std::hypot(r.cx - inner.cx, r.cy - inner.cy);
    const double d_outer = std::hypot(r.cx - outer.cx, r.cy - outer.cy);
    const double overlap_inner = m.inner_raceway_radius_m + m.roller_radius_m - d_inner;
    const double overlap_outer = d_outer + m.roller_radius_m - m.outer_raceway_radius_m;
    const double excess = std::max(overlap_inner, overlap_outer) - depth[j];
    // A NaN position is an overlap of any size.
    worst = std::isnan(excess) ? HUGE_VAL : std::max(worst, excess / m.roller_radius_m);
  }
  return worst;
}

// The first non-finite recorded value, or "". The cage slip ratio is NaN by definition where the
// pure-rolling cage speed is 0 (a standing shaft, t = 0 of a ramp): those samples are not counted.
std::string FirstNonFinite(const Recorder& rec, const BearingModel& model) {
  const std::vector<double>& time = rec.Find("/time")->data;
  for (const Recorder::Series& s : rec.series())
    for (std::size_t i = 0; i < s.data.size(); ++i) {
      if (std::isfinite(s.data[i])) continue;
      const std::size_t sample = i / std::max(1, s.cols);
      if (s.path == "/cage/slip_ratio" && sample < time.size() &&
          model.TheoreticalCageSpeed(time[sample]) == 0.0)
        continue;
      return s.path + " sample " + std::to_string(sample) + " is " + Num(s.data[i]);
    }
  for (std::size_t c = 0; c < model.sensor_channels().size(); ++c) {
    const auto& a = rec.Acceleration(static_cast<int>(c));
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!std::isfinite(a[i]))
        return "acceleration channel " + std::to_string(c) + " sample " + std::to_string(i) +
               " is " + Num(a[i]);
  }
  return "";
}

}  // namespace

const char* StressOutcomeName(StressOutcome outcome) {
  switch (outcome) {
    case StressOutcome::kRejected:
      return "rejected";
    case StressOutcome::kPassed:
      return "passed";
    case StressOutcome::kFailed:
      return "FAILED";
  }
  return "?";
}

std::string StressCase::Reproduce() const {
  std::string s;
  for (const auto& o : overrides) {
    if (!s.empty()) s += ' ';
    s += "--set '";
    s += o;
    s += '\'';
  }
  return s;
}

bool StressOptions::Validate(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (scenes < 1 || scenes > 100000) return fail("stress: scenes must be in [1, 100000]");
  if (fidelity == Fidelity::kAuto)
    return fail(std::string("stress: fidelity must be \"hybrid\", \"lumped\" or \"fe\" (got \"") +
                FidelityName(fidelity) + "\")");
  if (!(max_duration_s >= 1e-3 && max_duration_s <= 1.0))
    return fail("stress: max duration must be in [0.001, 1] s");
  if (!(min_mesh_size_mm >= 0.25 && min_mesh_size_mm <= max_mesh_size_mm &&
        max_mesh_size_mm <= 5.0))
    return fail("stress: mesh sizes must satisfy 0.25 <= min <= max <= 5 mm");
  if (!(beyond_fraction >= 0 && beyond_fraction <= 1))
    return fail("stress: beyond fraction must be in [0, 1]");
  if (!(max_energy_error_percent > 0) || !(max_overlap_fraction > 0))
    return fail("stress: the check bounds must be > 0");
  return true;
}

StressCase DrawScene(const StressOptions& o, int index) {
  Draw d(o.seed, index);
  StressCase c;
  c.index = index;
  Set(&c, "model.fidelity", std::string("\"") + FidelityName(o.fidelity) + "\"");
  Set(&c, "solver.threads", "1");
  // Speed: a standing shaft one time in ten, a sudden start (no ramp) one time in seven.
  Set(&c, "operation.speed_rpm", d.Chance(0.1) ? "0.0" : Num(d.Uniform(0.0, 20000.0)));
  Set(&c, "operation.ramp_s", d.Chance(1.0 / 7) ? "0.0" : Num(d.Uniform(1e-4, 0.01)));
  Set(&c, "operation.radial_load_n", Num(d.Uniform(0.0, 50000.0)));
  // A load step (no ramp) one time in three.
  Set(&c, "operation.load_ramp_s", d.Chance(1.0 / 3) ? "0.0" : Num(d.Uniform(1e-4, 0.01)));
  Set(&c, "bearing.diametral_clearance_mm", Num(d.Uniform(0.0, 0.1)));
  // Spalls: a healthy bearing one time in five, else 1-13 spalled rollers.
  const int spalled = d.Chance(0.2) ? 0 : d.Integer(1, kRollers);
  std::vector<int> rollers(kRollers);
  std::iota(rollers.begin(), rollers.end(), 0);
  for (int i = kRollers - 1; i > 0; --i) std::swap(rollers[i], rollers[d.Integer(0, i)]);
  if (spalled == 0) Set(&c, "defects", "[]");
  for (int k = 0; k < spalled; ++k) {
    const std::string p = "defects." + std::to_string(k) + ".";
    const double width = d.Uniform(0.05, 3.0);
    const double r = kRollerRadiusMm;
    const double sag = r - std::sqrt(r * r - 0.25 * width * width);
    Set(&c, p + "roller", std::to_string(rollers[k]));
    Set(&c, p + "width_mm", Num(width));
    Set(&c, p + "depth_mm", Num(d.Uniform(1.05 * sag + 0.01, 0.499 * r)));
    Set(&c, p + "angle_deg", Num(d.Uniform(-180.0, 180.0)));
  }
  const double mu_s = d.Uniform(0.0, 0.3);
  Set(&c, "friction.mu_static", Num(mu_s));
  Set(&c, "friction.mu_dynamic", Num(mu_s * d.Uniform(0.0, 1.0)));
  Set(&c, "damping.ratio", Num(d.Uniform(0.0, 0.2)));
  Set(&c, "mesh.size_mm", Num(d.LogUniform(o.min_mesh_size_mm, o.max_mesh_size_mm)));
  Set(&c, "run.duration_s", Num(d.LogUniform(1e-3, o.max_duration_s)));
  c.beyond_range = d.Chance(o.beyond_fraction);
  if (c.beyond_range) {
    if (spalled == 0) {  // the spall keys need a spall to go beyond
      c.overrides.erase(std::find(c.overrides.begin(), c.overrides.end(), "defects=[]"));
      Set(&c, "defects.0.roller", "0");
    }
    DrawBeyond(d, &c);
  }
  return c;
}

void RunScene(const StressOptions& o, StressCase* c) {
  const auto t0 = std::chrono::steady_clock::now();
  auto finish = [&](StressOutcome outcome, const std::string& reason) {
    c->outcome = outcome;
    c->reason = reason;
    c->wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  const std::string name = "stress#" + std::to_string(c->index);
  Scene scene;
  try {
    scene = ParseScene("", name, c->overrides);
  } catch (const InputError& e) {
    return finish(StressOutcome::kRejected, e.what());
  }
  try {
    SimulationOptions so;  // no output path: results stay in memory
    const Simulation* running = nullptr;
    double worst = 0.0;
    so.progress = [&](const SimulationProgress&) {
      if (running) worst = std::max(worst, WorstOverlap(running->model()));
    };
    std::unique_ptr<Simulation> simulation;
    try {
      simulation = std::make_unique<Simulation>(scene, so);
    } catch (const InputError& e) {
      return finish(StressOutcome::kRejected, e.what());
    }
    running = simulation.get();
    const SimulationSummary s = simulation->Run();
    c->steps = s.steps;
    c->max_overlap_fraction = worst;
    const solver::Energies& e = s.energies;
    c->energy_error_percent = 100.0 * e.BalanceError();
    if (!s.completed) return finish(StressOutcome::kFailed, "run did not complete");
    const std::string bad = FirstNonFinite(simulation->recorder(), simulation->model());
    if (!bad.empty()) return finish(StressOutcome::kFailed, "non-finite output: " + bad);
    // Energies below a millijoule (a standing, unloaded bearing) are not judged, as in simulate.
    if (e.Scale() >= 1e-3 && !(c->energy_error_percent <= o.max_energy_error_percent))
      return finish(StressOutcome::kFailed,
                    "energy balance error " + Num(c->energy_error_percent) + " % > " +
                        Num(o.max_energy_error_percent) + " %");
    if (!(worst <= o.max_overlap_fraction))
      return finish(StressOutcome::kFailed,
                    "a roller overlaps a race by " + Num(worst) +
                        " roller radii beyond its spall depth (through the race)");
    return finish(StressOutcome::kPassed, "");
  } catch (const std::exception& e) {
    return finish(StressOutcome::kFailed, e.what());
  }
}

StressSummary RunStress(const StressOptions& options) {
  std::string error;
  if (!options.Validate(&error)) throw InputError(error);
  StressSummary sum;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < options.scenes; ++i) {
    StressCase c = DrawScene(options, i);
    RunScene(options, &c);
    (c.outcome == StressOutcome::kRejected ? sum.rejected
     : c.outcome == StressOutcome::kPassed ? sum.passed
                                           : sum.failed)++;
    if (options.progress) options.progress(c);
    sum.cases.push_back(std::move(c));
  }
  sum.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sum;
}

std::string StressSummary::BriefReport() const {
  std::ostringstream os;
  os << "stress: " << cases.size() << " scenes: " << passed << " passed, " << rejected
     << " rejected up front, " << failed << " FAILED (" << Num(wall_seconds) << " s)";
  return os.str();
}

std::string StressSummary::Table() const {
  std::ostringstream os;
  char line[256];
  std::snprintf(line,
                sizeof line,
                "%5s %-9s %6s %9s %10s %9s %8s  %s\n",
                "scene",
                "outcome",
                "beyond",
                "steps",
                "energy_%",
                "overlap",
                "wall_s",
                "reason");
  os << line;
  for (const StressCase& c : cases) {
    std::snprintf(line,
                  sizeof line,
                  "%5d %-9s %6s %9ld %10.2e %9.2e %8.2f  ",
                  c.index,
                  StressOutcomeName(c.outcome),
                  c.beyond_range ? "yes" : "no",
                  c.steps,
                  c.energy_error_percent,
                  c.max_overlap_fraction,
                  c.wall_seconds);
    os << line << c.reason.substr(0, 160) << "\n";
  }
  for (const StressCase& c : cases)
    if (c.outcome == StressOutcome::kFailed)
      os << "FAILED scene " << c.index << ": " << c.reason
         << "\n  reproduce: spall simulate /dev/null -o stress.h5 " << c.Reproduce() << "\n";
  return os.str();
}

std::string StressSummary::ToJson(int indent) const {
  nlohmann::ordered_json j;
  j["scenes"] = cases.size();
  j["passed"] = passed;
  j["rejected"] = rejected;
  j["failed"] = failed;
  j["wall_seconds"] = wall_seconds;
  auto& arr = j["cases"] = nlohmann::ordered_json::array();
  for (const StressCase& c : cases)
    arr.push_back({{"index", c.index},
                   {"outcome", StressOutcomeName(c.outcome)},
                   {"beyond_range", c.beyond_range},
                   {"reason", c.reason},
                   {"energy_error_percent", c.energy_error_percent},
                   {"max_overlap_fraction", c.max_overlap_fraction},
                   {"steps", c.steps},
                   {"wall_seconds", c.wall_seconds},
                   {"overrides", c.overrides}});
  return j.dump(indent);
}

}  // namespace spallkit::sim::stress
