#include "sim/bearing/lumped_model.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>

#include "core/checkpoint_io.h"
#include "core/constants.h"
#include "core/error.h"
#include "sim/bearing/model_builder.h"
#include "sim/bearing/raceway_kernel.h"
#include "sim/solver/stable_step.h"

namespace spallkit::sim {

// The scene whose housing is fitted: the hybrid model's housing mesh at the fit's size.
Scene HousingFitScene(const Scene& scene, const LumpedOptions& options) {
  Scene s = scene;
  s.model.fidelity = Fidelity::kHybrid;
  s.mesh.size_m = s.mesh.contact_size_m = options.fit_mesh_size_m;
  s.mesh.adapter_size_m = std::max(s.mesh.adapter_size_m, 0.5 * options.fit_mesh_size_m);
  s.defects.clear();
  return s;
}

double SensorPathVelocity(const HousingFit& fit,
                          int channel,
                          const std::vector<double>& f_down,
                          const std::vector<double>& f_x,
                          long newest) {
  double v = 0.0;
  const std::vector<double>* forces[2] = {&f_down, &f_x};
  for (int p = 0; p < 2; ++p) {
    const std::vector<double>& g = fit.sensor_response[channel][p];
    const std::vector<double>& f = *forces[p];
    const long n = static_cast<long>(g.size());
    // g[i] pairs with the force i samples back: f[newest - i], wrapped.
    long k = newest;
    for (long i = 0; i < n; ++i) {
      v += g[i] * f[k];
      k = k == 0 ? n - 1 : k - 1;
    }
  }
  return v;
}

namespace {

std::string CacheKey(const Scene& scene, const LumpedOptions& o) {
  std::ostringstream os;
  os.precision(17);
  const SceneGeometry& g = scene.geometry;
  const BearingGeometry& b = g.bearing;
  os << b.num_elements << ' ' << b.element_diameter_m << ' ' << b.pitch_diameter_m << ' '
     << b.contact_angle_rad << ' ' << g.thickness_m << ' ' << g.ring_width_m << ' '
     << g.diametral_clearance_m << ' ' << g.outer_ring_outer_diameter_m << ' ' << g.adapter_width_m
     << ' ' << g.adapter_height_m << ' ' << g.roller_phase_rad << ' '
     << scene.operation.radial_load_n << ' ' << scene.damping.ratio << ' '
     << scene.damping.reference_hz << ' ' << scene.mesh.adapter_size_m << ' '
     << AdapterModelName(scene.model.adapter) << ' ' << o.fit_mesh_size_m << ' ' << o.fit_duration_s
     << ' ' << o.fit_damping_ratio << ' ' << o.sensor_response_s << ' ' << o.sensor_sample_hz;
  for (const Material* m : {&scene.materials.outer_ring, &scene.materials.adapter})
    os << ' ' << m->youngs_modulus_pa << ' ' << m->poisson_ratio << ' ' << m->density_kg_m3;
  for (const Sensor& s : scene.sensors) {
    os << ' ' << s.name << ' ' << s.x_m << ' ' << s.y_m;
    for (Axis d : s.directions) os << ' ' << AxisName(d);
  }
  return os.str();
}

// Stribeck roller loads on the raceway: Q_j ~ cos^(10/9) of the angle from the load line, over
// the loaded half, scaled so that they add up to `load` along it.
class RacewayLoad : public solver::ForceContributor {
 public:
  RacewayLoad(const RacewayKernel& kernel,
              const std::vector<double>& angles,
              double load_angle,
              double load,
              double ramp_s)
      : kernel_(kernel), angles_(angles), ramp_(ramp_s) {
    double sum = 0.0;
    for (double th : angles_) {
      const double c = std::cos(th - load_angle);
      q_.push_back(c > 0 ? std::pow(c, 10.0 / 9.0) : 0.0);
      sum += q_.back() * std::max(0.0, c);
    }
    for (double& q : q_) q *= load / sum;
  }
  void AddForces(fe::NodalState& state, double t, double /*dt*/) override {
    const double s = std::min(1.0, t / ramp_);
    const double r = s * s * (3.0 - 2.0 * s);  // smooth ramp
    for (size_t j = 0; j < angles_.size(); ++j)
      if (q_[j] > 0)
        kernel_.Spread(
            state, angles_[j], r * q_[j] * std::cos(angles_[j]), r * q_[j] * std::sin(angles_[j]));
  }
  std::string Name() const override { return "raceway_load"; }
  // Load-weighted radial approach of the raceway (m): the rigid-ring equivalent displacement.
  double Approach(const fe::NodalState& s, double load) const {
    double w = 0.0;
    for (size_t j = 0; j < angles_.size(); ++j) {
      if (!(q_[j] > 0)) continue;
      const double r = kernel_.Radius(s, angles_[j]) - kernel_.radius();
      w += q_[j] * r;
    }
    return w / load;
  }

 private:
  const RacewayKernel& kernel_;
  std::vector<double> angles_, q_;
  double ramp_;
};

// A force (fx, fy) (1 - cos(pi t / h)) / 2 on the raceway at `angle` for 0 < t < 2h: the
// impulse of (fx, fy) held for h, centred at t = h, smooth (band-limited to about 1 / h).
class RacewayPulse : public solver::ForceContributor {
 public:
  RacewayPulse(const RacewayKernel& kernel, double angle, double fx, double fy, double h)
      : kernel_(kernel), angle_(angle), fx_(fx), fy_(fy), h_(h) {}
  void AddForces(fe::NodalState& state, double t, double /*dt*/) override {
    if (!(t > 0 && t < 2.0 * h_)) return;
    const double s = 0.5 - 0.5 * std::cos(kPi * t / h_);
    kernel_.Spread(state, angle_, s * fx_, s * fy_);
  }
  std::string Name() const override { return "raceway_pulse"; }

 private:
  const RacewayKernel& kernel_;
  double angle_, fx_, fy_, h_;
};

// The FE housing alone, as the fit runs it: it reads motions only, so no energy terms.
BearingModelOptions HousingOnly(BearingModelOptions options) {
  options.housing_only = true;
  options.energy_books = false;
  return options;
}

// The sensor path's impulse responses (see HousingFit::sensor_response).
void ProbeSensorResponse(const Scene& fs, const BearingModelOptions& options, HousingFit* fit) {
  const LumpedOptions& lo = options.lumped;
  const BearingModelOptions o = HousingOnly(options);
  constexpr double kForce = 1000.0;
  const double h = 1.0 / lo.sensor_sample_hz, load_line = -0.5 * kPi;
  const int n = std::max(8, static_cast<int>(std::lround(lo.sensor_response_s / h)));
  for (int p = 0; p < 2; ++p) {
    FeBearingModel model(fs, o);
    const BearingMesh& mesh = model.bearing_mesh();
    const auto& channels = model.sensor_channels();
    fit->sensor_response.resize(channels.size(), std::vector<std::vector<double>>(2));
    RacewayKernel kernel(mesh.mesh,
                         "outer_ring.raceway",
                         mesh.outer_raceway_radius_m,
                         options.hybrid.spread_half_width_m);
    RacewayPulse pulse(kernel, load_line, p == 1 ? kForce : 0.0, p == 0 ? -kForce : 0.0, h);
    solver::ExplicitSolver& solver = model.solver();
    solver.AddContributor(&pulse);
    // The mean velocity over each sample, (u(t_i + h) - u(t_i)) / h, t_i = i h + h / 2 (the
    // pulse is centred half a sample later than a force held over [0, h)): with the smooth
    // pulse, the mesh's modes far above the sample rate stay out of the response (a box pulse
    // or a point velocity would alias them).
    std::vector<double> u_old(channels.size(), 0.0);
    for (int i = 0; i < n; ++i) {
      solver.Run((i + 1.5) * h);
      const fe::NodalState& st = solver.state();
      for (size_t c = 0; c < channels.size(); ++c) {
        const int node = channels[c].node;
        const double u =
            channels[c].direction == Axis::kX ? st.x[node] - st.x0[node] : st.y[node] - st.y0[node];
        fit->sensor_response[c][p].push_back((u - u_old[c]) / h / kForce);
        u_old[c] = u;
      }
    }
  }
  // Taper the last quarter (half Hann) and remove the sum with the taper's shape: a constant
  // force then gives no velocity, as the housing at rest under it.
  const int tail = n / 4;
  std::vector<double> w(n, 1.0);
  for (int i = n - tail; i < n; ++i)
    w[i] = 0.5 + 0.5 * std::cos(kPi * (i - (n - tail) + 1) / (tail + 1));
  double w_sum = 0.0;
  for (double x : w) w_sum += x;
  for (auto& channel : fit->sensor_response)
    for (std::vector<double>& g : channel) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += (g[i] *= w[i]);
      for (int i = 0; i < n; ++i) g[i] -= sum * w[i] / w_sum;
    }
}

HousingFit ComputeHousingFit(const Scene& scene, const BearingModelOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const LumpedOptions& lo = options.lumped;
  const Scene fs = HousingFitScene(scene, lo);
  HousingFit fit;
  const double load = std::max(scene.operation.radial_load_n, 1000.0);
  // Case 0: load along +x; case 1: along -y (the scene's load direction).
  const double load_angle[2] = {0.0, -0.5 * kPi};
  std::vector<std::vector<double>> channel_disp(2);
  for (int d = 0; d < 2; ++d) {
    const BearingModelOptions o = HousingOnly(options);
    Scene s = fs;
    s.damping.ratio = lo.fit_damping_ratio;
    s.damping.reference_hz = 3000.0;
    FeBearingModel model(s, o);
    const BearingMesh& mesh = model.bearing_mesh();
    RacewayKernel kernel(mesh.mesh,
                         "outer_ring.raceway",
                         mesh.outer_raceway_radius_m,
                         options.hybrid.spread_half_width_m);
    RacewayLoad pattern(
        kernel, mesh.roller_angles_rad, load_angle[d], load, 0.25 * lo.fit_duration_s);
    solver::ExplicitSolver& solver = model.solver();
    solver.AddContributor(&pattern);
    solver.Run(0.8 * lo.fit_duration_s);
    const double c_early = pattern.Approach(solver.state(), load);
    solver.Run(lo.fit_duration_s);
    const fe::NodalState& st = solver.state();
    const double c = pattern.Approach(st, load);
    if (!(c > 0))
      throw InputError(
          "lumped model: the housing fit found no raceway approach under load "
          "(check the adapter and ring geometry)");
    fit.residual_motion = std::max(fit.residual_motion, std::abs(c - c_early) / c);
    // Displacement of a unit rigid-ring motion along d is the direction vector; c is along
    // the load direction, so the ring moves by c along (cos, sin) of the load angle.
    double m2 = 0.0;
    for (size_t i = 0; i < st.size(); ++i) {
      const double ux = st.x[i] - st.x0[i], uy = st.y[i] - st.y0[i];
      m2 += st.mass[i] * (ux * ux + uy * uy);
    }
    fit.stiffness[d] = load / c;
    fit.mass[d] = m2 / (c * c);
    fit.damping[d] = 4.0 * kPi * scene.damping.ratio * scene.damping.reference_hz * fit.mass[d];
    const double ex = std::cos(load_angle[d]), ey = std::sin(load_angle[d]);
    for (const SensorChannel& ch : model.sensor_channels()) {
      const double u =
          (st.x[ch.node] - st.x0[ch.node]) * ex + (st.y[ch.node] - st.y0[ch.node]) * ey;
      channel_disp[d].push_back(u / c);
    }
  }
  // Each channel's gain from the load case along its own direction.
  FeBearingModel probe(fs, HousingOnly(options));
  const auto& channels = probe.sensor_channels();
  for (size_t k = 0; k < channels.size(); ++k)
    fit.sensor_gain.push_back(channel_disp[channels[k].direction == Axis::kX ? 0 : 1][k]);
  if (lo.sensor_response_s > 0) ProbeSensorResponse(fs, options, &fit);
  fit.fit_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return fit;
}

}  // namespace

double HousingFit::Frequency(int d) const {
  return std::sqrt(stiffness[d] / mass[d]) / (2.0 * kPi);
}

HousingFit FitHousing(const Scene& scene, const BearingModelOptions& options) {
  static std::mutex mutex;
  static std::map<std::string, HousingFit> cache;
  const std::string key = CacheKey(scene, options.lumped);
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end()) {
      HousingFit f = it->second;
      f.fit_wall_s = 0.0;
      return f;
    }
  }
  HousingFit fit = ComputeHousingFit(scene, options);
  std::lock_guard<std::mutex> lock(mutex);
  cache.emplace(key, fit);
  return fit;
}

LumpedBearingModel::LumpedBearingModel(const Scene& scene, const BearingModelOptions& options)
    : BearingModel(scene, options),
      housing_(MeshBearingHousing(HousingFitScene(scene, options.lumped))),
      fit_(FitHousing(scene, options)),
      rollers_(scene,
               housing_,
               std::min(fit_.mass[0], fit_.mass[1]),
               options_.hybrid,  // the base's: with the scene's settings
               options_.cage_guide),
      race_(housing_.outer_raceway_radius_m) {
  std::string err;
  if (!options_.hybrid.IsValid(&err)) throw InputError(err);
  // Sensor channels in the FE models' order: every scene sensor, each of its directions.
  for (const Sensor& sensor : scene_.sensors)
    for (Axis dir : sensor.directions) channels_.push_back({sensor.name, dir, -1, 0.0});
  if (channels_.size() != fit_.sensor_gain.size())
    throw InputError("lumped model: the housing fit has " +
                     std::to_string(fit_.sensor_gain.size()) + " sensor channels, the scene " +
                     std::to_string(channels_.size()));
  // Stable step, 2 / omega (sqrt(1 + zeta^2) - zeta) for every oscillator:
  //  - a roller: its translation normal to the races carries one Palmgren spring k_n per
  //    race in a healthy bearing, up to three in a spall passage (two rim edges on one race,
  //    one on the other), so a spalled bearing's steps are taken with three (its long step is
  //    set by the energy error of the contacts' ringing, not by stability: see below); under
  //    the fast rule its long step is on two (a passage below spall_step_min_load_fraction of
  //    the mean roller load needs no more: the Palmgren stiffness goes as Q^0.1, so three
  //    springs there are softer than two at the bound, twice the radial load). Along
  //    the orbit and in rotation the stick springs k_t = ratio k_n (two on one race, one on
  //    the other) on rim points of a disc (I = m r^2 / 2) give omega^2 = 6.6 k_t / m, plus the
  //    cage wall k_c on the translation.
  //    The hybrid's bound 6 (k_n + k_t) / m is the sum of the two, 1.8x in omega^2; the rigid
  //    ring's mass is large against the roller's, so the ring side does not limit.
  //    With friction.model = "ehl" the race contacts have no stick spring (the traction curve
  //    of the slide-to-roll ratio, implicit in the slip, is stable at any step): only the
  //    pocket walls' (k_c, and their stick springs 3.3 ratio k_c on the rim).
  //  - the ring oscillators, with their damping.
  // A bearing with spalled rollers takes the smaller safety between its passages, but under the
  // fast rule (the scene's [solver] lumped_step).
  for (int j = 0; j < rollers_.num_rollers(); ++j)
    if (rollers_.profile(j).spalled) spalled_.push_back(j);
  const bool fast = scene_.solver.lumped_step == LumpedStep::kFast;
  const bool two_springs = spalled_.empty() || fast;  // the long step's bound
  const double safety =
      two_springs ? options_.lumped.time_step_safety : options_.lumped.spalled_time_step_safety;
  {
    const double kn = rollers_.bound_normal_stiffness();
    const double ratio = options_.hybrid.tangential_stiffness_ratio;
    const double kc = options_.hybrid.cage_stiffness_n_per_m;
    double m_min = rollers_.roller_mass(0);
    for (int j = 0; j < rollers_.num_rollers(); ++j)
      m_min = std::min(m_min, rollers_.roller_mass(j));
    const double k_rim = scene_.friction.model == contact::TractionModel::kEhl
                             ? kc * (1.0 + 3.3 * ratio)
                             : 7.0 * ratio * kn + kc;
    const double zeta = options_.hybrid.contact_damping_ratio;
    auto limit = [&](double springs) {
      return solver::DampedStableStep(std::sqrt(std::max(springs * kn, k_rim) / m_min), zeta);
    };
    dt_stable_ = safety * limit(two_springs ? 2.0 : 3.0);
    dt_spall_ = (fast ? options_.lumped.fast_spall_time_step_safety
                      : options_.lumped.spall_time_step_safety) *
                limit(3.0);
  }
  if (!fit_.sensor_response.empty()) {
    for (auto& h : history_) h.assign(fit_.sensor_response[0][0].size(), 0.0);
    sensor_prev_.assign(channels_.size(), 0.0);
    sensor_last_.assign(channels_.size(), 0.0);
  }
  for (int d = 0; d < 2; ++d) {
    const double omega = std::sqrt(fit_.stiffness[d] / fit_.mass[d]);
    const double zeta = fit_.damping[d] / (2.0 * fit_.mass[d] * omega);
    dt_stable_ = std::min(dt_stable_, safety * solver::DampedStableStep(omega, zeta));
  }
  dt_spall_ = std::min(dt_spall_, dt_stable_);
  const int z = rollers_.num_rollers();
  spall_min_load_ =
      options_.lumped.spall_step_min_load_fraction * std::abs(scene_.operation.radial_load_n) / z;
  loaded_passage_.assign(z, 0);
}

void LumpedBearingModel::Step() {
  // The short step while the speed and load ramp up (the rollers are spun up by sliding) and
  // in loaded spall passages, where the energy error is made (docs/BEARING_MODEL.md): a passage
  // counts from the moment in it the roller carries spall_min_load_ (the last step's loads) to
  // its end, and the short step lingers after it while its impacts ring down.
  const LumpedOptions& lo = options_.lumped;
  const double ramps = 2.0 * std::max(scene_.operation.ramp_s, scene_.operation.load_ramp_s);
  const double min_spin =
      spalled_.empty() ? 0.0 : lo.spall_step_min_spin_ratio * std::abs(rollers_.ShaftSpeed(time_));
  for (int j : spalled_) {
    if (!rollers_.SpallNearRace(j, lo.spall_step_margin_rad, min_spin)) {
      loaded_passage_[j] = 0;
      continue;
    }
    if (rollers_.OuterForce(j) + rollers_.InnerForce(j) >= spall_min_load_) loaded_passage_[j] = 1;
    if (loaded_passage_[j]) short_step_until_ = time_ + lo.spall_step_linger_s;
  }
  const bool refine = time_ < ramps || time_ < short_step_until_;
  const double dt = refine ? dt_spall_ : dt_stable_;
  race_.fx_ = race_.fy_ = 0.0;
  rollers_.Step(race_, time_, dt);
  // Ring: roller reactions, housing spring and damper at x^n, v^(n-1/2).
  const double dt_avg = 0.5 * (dt_prev_ + dt);
  double* u[2] = {&race_.x_, &race_.y_};
  double* v[2] = {&race_.vx_, &race_.vy_};
  const double f_rollers[2] = {race_.fx_, race_.fy_};
  spring_half_ = damping_half_ = 0.0;
  for (int d = 0; d < 2; ++d) {
    const double spring = -fit_.stiffness[d] * *u[d];
    const double damper = -fit_.damping[d] * *v[d];
    const double v_old = *v[d];
    ring_v_old_[d] = v_old;
    *v[d] += dt_avg * (f_rollers[d] + spring + damper) / fit_.mass[d];
    // Work of the housing forces over the half steps around t^n (the solver's rule).
    const double v_mid = 0.5 * (v_old + *v[d]);
    spring_energy_ -= spring * v_mid * dt_avg;
    housing_damping_work_ -= damper * v_mid * dt_avg;
    spring_half_ -= 0.5 * spring * *v[d] * dt_avg;
    damping_half_ -= 0.5 * damper * *v[d] * dt_avg;
    *u[d] += dt * *v[d];
  }
  if (!fit_.sensor_response.empty()) SensorSample(-f_rollers[1], f_rollers[0], dt);
  dt_prev_ = dt;
  dt_ = dt;
  time_ += dt;
  ++step_;
}

void LumpedBearingModel::SensorSample(double f_down, double f_x, double dt) {
  const double h = 1.0 / options_.lumped.sensor_sample_hz;
  sample_force_[0] += f_down * dt, sample_force_[1] += f_x * dt;
  sample_time_ += dt;
  if (sample_time_ < h) return;
  // A sample is complete: its mean force joins the history, each channel's velocity is the
  // convolution of the history with its responses.
  const long n = static_cast<long>(history_[0].size());
  history_pos_ = (history_pos_ + 1) % n;
  for (int p = 0; p < 2; ++p) {
    history_[p][history_pos_] = sample_force_[p] / sample_time_;
    sample_force_[p] = 0.0;
  }
  sample_time_ = 0.0;
  for (size_t c = 0; c < sensor_last_.size(); ++c) {
    sensor_prev_[c] = sensor_last_[c];
    sensor_last_[c] =
        SensorPathVelocity(fit_, static_cast<int>(c), history_[0], history_[1], history_pos_);
  }
}

solver::SolverSummary LumpedBearingModel::Run(double end_time) {
  solver::SolverSummary sum;
  const auto t0 = std::chrono::steady_clock::now();
  if (!started_) {
    started_ = true;
    if (observer_) observer_();
  }
  const long first = step_;
  double min_dt = std::numeric_limits<double>::infinity(), max_dt = 0.0;
  while (time_ < end_time) {
    Step();
    min_dt = std::min(min_dt, dt_), max_dt = std::max(max_dt, dt_);
    if (observer_) observer_();
  }
  sum.steps = step_ - first;
  sum.time = time_;
  sum.min_time_step = sum.steps > 0 ? min_dt : 0.0;
  sum.max_time_step = sum.steps > 0 ? max_dt : 0.0;
  sum.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sum.threads = 1;
  sum.energies = energies();
  return sum;
}

solver::Energies LumpedBearingModel::energies() const {
  solver::Energies e;
  e.kinetic = rollers_.CentredKineticEnergy();
  for (int d = 0; d < 2; ++d)
    e.kinetic += 0.5 * fit_.mass[d] * ring_v_old_[d] * (d == 0 ? race_.vx_ : race_.vy_);
  e.internal = spring_energy_ - spring_half_;
  e.contact = rollers_.ContactEnergy();
  e.friction = rollers_.FrictionWork();
  e.damping = rollers_.DampingWork() + housing_damping_work_ - damping_half_;
  e.external = e.external_loads = rollers_.ExternalWork();
  return e;
}

BodyMotion LumpedBearingModel::RollerMotion(int j) const {
  const PlanarBody& b = rollers_.roller(j);
  return {b.x, b.y, b.vx, b.vy, b.omega};
}

BodyMotion LumpedBearingModel::CageMotion() const {
  const PlanarBody& b = rollers_.cage();
  return {b.x, b.y, b.vx, b.vy, b.omega};
}

BodyMotion LumpedBearingModel::InnerRingMotion() const {
  const PlanarBody& b = rollers_.shaft();
  return {b.x, b.y, b.vx, b.vy, speed_(time_)};
}

double LumpedBearingModel::SensorVelocity(int channel) const {
  const SensorChannel& ch = channels_[channel];
  if (fit_.sensor_response.empty())
    return fit_.sensor_gain[channel] * (ch.direction == Axis::kX ? race_.vx_ : race_.vy_);
  // Between the last two samples (one sample of delay: a continuous velocity to differentiate).
  const double s = sample_time_ * options_.lumped.sensor_sample_hz;
  return sensor_prev_[channel] + s * (sensor_last_[channel] - sensor_prev_[channel]);
}

std::string LumpedBearingModel::SaveState() const {
  CheckpointWriter out;
  for (double x : {time_,
                   dt_,
                   dt_prev_,
                   spring_energy_,
                   housing_damping_work_,
                   race_.x_,
                   race_.y_,
                   race_.vx_,
                   race_.vy_,
                   ring_v_old_[0],
                   ring_v_old_[1],
                   spring_half_,
                   damping_half_,
                   short_step_until_})
    out.Put(x);
  out.Put<std::int64_t>(step_);
  out.Put<std::uint8_t>(started_ ? 1 : 0);
  for (double x : {sample_force_[0], sample_force_[1], sample_time_}) out.Put(x);
  out.Put<std::int64_t>(history_pos_);
  for (const auto* v : {&history_[0], &history_[1], &sensor_prev_, &sensor_last_})
    out.PutVector(*v);
  out.PutVector(loaded_passage_);
  out.PutBytes(rollers_.SaveState());
  return out.Take();
}

void LumpedBearingModel::LoadState(const std::string& bytes) {
  CheckpointReader in(bytes, "lumped model state");
  for (double* x : {&time_,
                    &dt_,
                    &dt_prev_,
                    &spring_energy_,
                    &housing_damping_work_,
                    &race_.x_,
                    &race_.y_,
                    &race_.vx_,
                    &race_.vy_,
                    &ring_v_old_[0],
                    &ring_v_old_[1],
                    &spring_half_,
                    &damping_half_,
                    &short_step_until_})
    *x = in.Get<double>();
  step_ = static_cast<long>(in.Get<std::int64_t>());
  started_ = in.Get<std::uint8_t>() != 0;
  for (double* x : {&sample_force_[0], &sample_force_[1], &sample_time_}) *x = in.Get<double>();
  history_pos_ = static_cast<long>(in.Get<std::int64_t>());
  for (auto* v : {&history_[0], &history_[1], &sensor_prev_, &sensor_last_})
    in.GetVectorInto(v, "lumped model sensor state");
  in.GetVectorInto(&loaded_passage_, "lumped model spall passages");
  if (history_pos_ < 0 ||
      (history_pos_ > 0 && history_pos_ >= static_cast<long>(history_[0].size())))
    throw InputError("lumped model state: bad sensor history position");
  rollers_.LoadState(in.GetBytes());
}

std::string LumpedBearingModel::Describe() const {
  std::ostringstream os;
  os.precision(4);
  const RollerContacts& r = rollers_;
  os << "model: lumped (rigid rollers, cage and inner ring with exact profiles; rigid outer ring "
        "on the fitted housing): Palmgren K_c = "
     << r.contact_stiffness() / std::pow(1e3, 10.0 / 9.0) * 1e-3 << " kN/mm^(10/9), roller mass "
     << r.roller_mass(0) * 1e3 << " g, cage " << r.cage_mass() * 1e3 << " g, inner ring "
     << r.shaft_mass() * 1e3 << " g; step " << dt_stable_ * 1e9 << " ns (" << dt_spall_ * 1e9
     << " ns in the ramps and loaded spall passages; " << LumpedStepName(scene_.solver.lumped_step)
     << " step rule)";
  os << "\nhousing fit (" << options_.lumped.fit_mesh_size_m * 1e3 << " mm FE housing, "
     << (fit_.fit_wall_s > 0 ? "computed in " : "cached");
  if (fit_.fit_wall_s > 0) os << fit_.fit_wall_s << " s";
  os << ", residual motion " << fit_.residual_motion * 100 << " %):";
  for (int d = 0; d < 2; ++d)
    os << (d == 0 ? " x: " : "; y: ") << fit_.stiffness[d] * 1e-9 << " kN/um, " << fit_.mass[d]
       << " kg, " << fit_.Frequency(d) << " Hz";
  for (size_t c = 0; c < channels_.size(); ++c) {
    os << "\nsensor " << channels_[c].sensor << " " << AxisName(channels_[c].direction) << ": ";
    if (fit_.sensor_response.empty())
      os << "gain " << fit_.sensor_gain[c] << " of the ring's motion";
    else
      os << "FE housing impulse responses, " << fit_.sensor_response[c][0].size() << " samples at "
         << options_.lumped.sensor_sample_hz * 1e-3 << " kHz";
  }
  return os.str();
}

}  // namespace spallkit::sim
