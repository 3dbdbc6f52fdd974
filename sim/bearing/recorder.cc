#include "sim/bearing/recorder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/checkpoint_io.h"
#include "core/error.h"
#include "core/hdf5.h"

namespace spallkit::sim {
namespace {

constexpr const char* kEnergyTerms[] = {"kinetic",
                                        "internal",
                                        "hourglass",
                                        "contact",
                                        "friction",
                                        "damping",
                                        "external",
                                        "balance_error"};
constexpr int kNumEnergyTerms = 8;

double Wrap(double a) {  // to (-pi, pi]
  return a - 2.0 * std::numbers::pi * std::ceil((a - std::numbers::pi) / (2.0 * std::numbers::pi));
}

}  // namespace

Recorder::Recorder(const BearingModel& model, const RecorderOptions& options)
    : model_(model), options_(options) {
  if (!(options_.output_rate_hz > 0) || !(options_.duration_s > 0) || options_.fine_factor < 1)
    throw InputError("recorder: output_rate_hz and duration_s must be > 0, fine_factor >= 1");
  num_samples_ =
      static_cast<int>(std::floor(options_.duration_s * options_.output_rate_hz + 1e-9)) + 1;
  const int z = model_.num_rollers();
  auto add = [&](const std::string& path, int cols, const std::string& units) {
    series_.push_back({path, cols, units, false, {}});
    series_.back().data.reserve(static_cast<size_t>(num_samples_) * cols);
    return static_cast<int>(series_.size()) - 1;
  };
  idx_time_ = add("/time", 1, "s");
  if (Wants(Output::kContactForces)) {
    idx_outer_ = add("/contact/roller_outer", z, "N");
    idx_inner_ = add("/contact/roller_inner", z, "N");
    idx_cage_force_ = add("/contact/roller_cage", z, "N");
  }
  if (Wants(Output::kCage)) {
    idx_omega_ = add("/cage/omega", 1, "rad/s");
    idx_slip_ = add("/cage/slip_ratio", 1, "1");
    idx_cage_centre_ = add("/cage/centre", 2, "m");
  }
  if (Wants(Output::kRollers)) {
    idx_spin_ = add("/rollers/spin", z, "rad/s");
    idx_orbit_ = add("/rollers/orbit_angle", z, "rad");
  }
  if (Wants(Output::kEnergy)) {
    idx_energy_ = static_cast<int>(series_.size());
    for (const char* term : kEnergyTerms)
      add(std::string("/energy/") + term, 1, std::string(term) == "balance_error" ? "1" : "J");
  }
  accel_ = Wants(Output::kAcceleration) && !model_.sensor_channels().empty();
  if (accel_) {
    const size_t nc = model_.sensor_channels().size();
    fine_h_ = 1.0 / (options_.output_rate_hz * options_.fine_factor);
    fine_needed_ = static_cast<long long>(num_samples_ - 1) * options_.fine_factor + 1 +
                   8LL * options_.fine_factor;
    prev_v_.assign(nc, 0.0);
    last_fine_v_.assign(nc, 0.0);
    last_fine_a_.assign(nc, 0.0);
    decimators_.assign(nc, spallkit::StreamingDecimator(options_.fine_factor, 8));
    accel_out_.assign(nc, {});
  }
  last_orbit_.assign(z, std::numeric_limits<double>::quiet_NaN());
  if (Wants(Output::kField)) {
    if (model_.num_elements() == 0)
      throw InputError(
          "run.outputs: \"field\" needs a meshed model (model.fidelity \"fe\" or "
          "\"hybrid\"); the " +
          std::string(FidelityName(model_.fidelity())) + " model steps no mesh");
    if (!(options_.field_rate_hz > 0) || options_.field_rate_hz > options_.output_rate_hz)
      throw InputError("recorder: field_rate_hz must be in (0, output_rate_hz]");
    num_field_samples_ =
        static_cast<int>(std::floor(options_.duration_s * options_.field_rate_hz + 1e-9)) + 1;
    const int ne = model_.num_elements();
    idx_field_time_ = static_cast<int>(series_.size());
    series_.push_back({"/field/time", 1, "s", false, {}});
    idx_field_ = static_cast<int>(series_.size());
    series_.push_back({"/field/von_mises", ne, "Pa", false, {}});
    series_.back().data.reserve(static_cast<size_t>(num_field_samples_) * ne);
  }
}

bool Recorder::Wants(Output output) const { return Asks(options_.outputs, output); }

const Recorder::Series* Recorder::Find(const std::string& path) const {
  for (const Series& s : series_)
    if (s.path == path) return &s;
  return nullptr;
}

void Recorder::PushFine(int c, double a) {
  if (static_cast<int>(accel_out_[c].size()) >= num_samples_) return;
  last_fine_a_[c] = a;
  decimators_[c].Push(a, &accel_out_[c]);
  if (static_cast<int>(accel_out_[c].size()) > num_samples_) accel_out_[c].resize(num_samples_);
}

void Recorder::Observe() {
  const BearingModel& model = model_;
  const auto& channels = model_.sensor_channels();
  if (accel_) {
    auto vel = [&](int c) { return model.SensorVelocity(c); };
    if (model.step() == 0) {
      prev_t_ = 0.0;
      for (size_t c = 0; c < channels.size(); ++c) prev_v_[c] = last_fine_v_[c] = vel(c);
    } else {
      const double t_mid = model.time() - 0.5 * model.time_step();
      const double span = t_mid - prev_t_;
      while (fine_index_ < fine_needed_ && (fine_index_ + 0.5) * fine_h_ <= t_mid) {
        const double tau = (fine_index_ + 0.5) * fine_h_;
        const double w = span > 0 ? (tau - prev_t_) / span : 1.0;
        for (size_t c = 0; c < channels.size(); ++c) {
          const double v = prev_v_[c] + w * (vel(c) - prev_v_[c]);
          PushFine(static_cast<int>(c), (v - last_fine_v_[c]) / fine_h_);
          last_fine_v_[c] = v;
        }
        ++fine_index_;
      }
      prev_t_ = t_mid;
      for (size_t c = 0; c < channels.size(); ++c) prev_v_[c] = vel(c);
    }
  }
  while (next_sample_ < num_samples_ &&
         model.time() >= next_sample_ / options_.output_rate_hz - 1e-15)
    Sample();
  while (next_field_sample_ < num_field_samples_ &&
         model.time() >= next_field_sample_ / options_.field_rate_hz - 1e-15)
    SampleField();
}

void Recorder::SampleField() {
  series_[idx_field_time_].data.push_back(next_field_sample_ / options_.field_rate_hz);
  std::vector<double>& d = series_[idx_field_].data;
  const size_t at = d.size();
  d.resize(at + static_cast<size_t>(model_.num_elements()));
  model_.ElementVonMises(d.data() + at);
  ++next_field_sample_;
}

void Recorder::Sample() {
  const double tk = next_sample_ / options_.output_rate_hz;
  series_[idx_time_].data.push_back(tk);
  const int z = model_.num_rollers();
  if (idx_outer_ >= 0) {
    for (int j = 0; j < z; ++j) {
      series_[idx_outer_].data.push_back(model_.RollerOuterForce(j));
      series_[idx_inner_].data.push_back(model_.RollerInnerForce(j));
      series_[idx_cage_force_].data.push_back(model_.RollerCageForce(j));
    }
  }
  if (idx_omega_ >= 0) {
    const BodyMotion cage = model_.CageMotion();
    const double w = cage.omega;
    const double wt = model_.TheoreticalCageSpeed(model_.time());
    series_[idx_omega_].data.push_back(w);
    series_[idx_slip_].data.push_back(wt != 0.0 ? (w - wt) / wt
                                                : std::numeric_limits<double>::quiet_NaN());
    // The cage's mass centre (x, y): a roller-guided cage's pockets do not hold it on the
    // bearing's centre, and where it runs sets the rollers' spacing.
    series_[idx_cage_centre_].data.push_back(cage.cx);
    series_[idx_cage_centre_].data.push_back(cage.cy);
  }
  if (idx_spin_ >= 0) {
    for (int j = 0; j < z; ++j) {
      const BodyMotion m = model_.RollerMotion(j);
      series_[idx_spin_].data.push_back(m.omega);
      const double a = std::atan2(m.cy, m.cx);
      // Unwrapped: continuous over revolutions.
      last_orbit_[j] = std::isnan(last_orbit_[j]) ? a : last_orbit_[j] + Wrap(a - last_orbit_[j]);
      series_[idx_orbit_].data.push_back(last_orbit_[j]);
    }
  }
  if (idx_energy_ >= 0) {
    const solver::Energies e = model_.energies();
    const double v[kNumEnergyTerms] = {e.kinetic,
                                       e.internal,
                                       e.hourglass,
                                       e.contact,
                                       e.friction,
                                       e.damping,
                                       e.external,
                                       e.BalanceError()};
    for (int i = 0; i < kNumEnergyTerms; ++i) series_[idx_energy_ + i].data.push_back(v[i]);
  }
  ++next_sample_;
}

void Recorder::Finish() {
  if (!accel_) return;
  for (size_t c = 0; c < accel_out_.size(); ++c) {
    // Hold the last fine sample for the FIR look-ahead (mirror of the start priming).
    const double last = last_fine_a_[c];
    int guard = 0;
    while (static_cast<int>(accel_out_[c].size()) < num_samples_ &&
           guard++ < 64 * options_.fine_factor * (num_samples_ + 1))
      decimators_[c].Push(last, &accel_out_[c]);
    if (static_cast<int>(accel_out_[c].size()) > num_samples_) accel_out_[c].resize(num_samples_);
  }
}

void Recorder::Write(h5::File* file) const {
  const double fs = options_.output_rate_hz;
  for (const Series& s : series_) {
    if (s.cols == 1)
      file->WriteDataset(s.path, s.data);
    else
      file->WriteDataset2D(s.path, s.data, s.data.size() / s.cols, s.cols);
    file->SetAttribute(s.path, "units", s.units);
    const bool field = s.path.rfind("/field/", 0) == 0;
    if (s.path != "/time" && s.path != "/field/time")
      file->SetAttribute(s.path, "sample_rate_hz", field ? options_.field_rate_hz : fs);
  }
  if (idx_field_ >= 0) {
    const fe::Mesh& m = model_.bearing_mesh().mesh;
    std::vector<double> nodes, elements, part;
    for (int i = 0; i < m.num_nodes(); ++i) nodes.push_back(m.x[i]), nodes.push_back(m.y[i]);
    for (int e = 0; e < m.num_elements(); ++e) {
      for (int c = 0; c < 4; ++c) elements.push_back(m.quads[e][c]);
      part.push_back(m.element_part[e]);
    }
    file->WriteDataset2D("/field/nodes", nodes, m.num_nodes(), 2);
    file->SetAttribute("/field/nodes", "units", "m");
    file->WriteDataset2D("/field/elements", elements, m.num_elements(), 4);
    file->WriteDataset("/field/part", part);
    std::string names;
    for (const std::string& n : m.part_names) names += (names.empty() ? "" : ",") + n;
    file->SetAttribute("/field/part", "part_names", names);
  }
  if (accel_) {
    const auto& channels = model_.sensor_channels();
    bool wrote_y = false, wrote_x = false;
    for (size_t c = 0; c < channels.size(); ++c) {
      const std::string direction = AxisName(channels[c].direction);
      std::vector<std::string> paths = {"/signals/" + channels[c].sensor + "_" + direction};
      // The two public channels: first vertical (y) and first horizontal (x, called z as in
      // the paper's LS-DYNA axes) sensor direction.
      if (channels[c].direction == Axis::kY && !wrote_y)
        paths.push_back("/signals/accel_y"), wrote_y = true;
      if (channels[c].direction == Axis::kX && !wrote_x)
        paths.push_back("/signals/accel_z"), wrote_x = true;
      for (const std::string& p : paths) {
        file->WriteDataset(p, accel_out_[c]);
        file->SetAttribute(p, "units", "m/s^2");
        file->SetAttribute(p, "sample_rate_hz", fs);
        file->SetAttribute(p, "sensor", channels[c].sensor);
        file->SetAttribute(p, "direction", direction);
      }
    }
  }
}

std::string Recorder::SaveState() const {
  CheckpointWriter out;
  out.Put<std::int32_t>(num_samples_);
  out.Put<std::int32_t>(next_sample_);
  out.Put<std::uint64_t>(series_.size());
  for (const Series& s : series_) out.PutVector(s.data);
  out.Put<std::int64_t>(fine_index_);
  out.Put(prev_t_);
  out.PutVector(prev_v_);
  out.PutVector(last_fine_v_);
  out.PutVector(last_fine_a_);
  out.Put<std::uint64_t>(decimators_.size());
  for (size_t c = 0; c < decimators_.size(); ++c) {
    out.PutVector(decimators_[c].SaveState());
    out.PutVector(accel_out_[c]);
  }
  out.PutVector(last_orbit_);
  out.Put<std::int32_t>(next_field_sample_);
  return out.Take();
}

void Recorder::LoadState(const std::string& bytes) {
  CheckpointReader r(bytes, "checkpoint: recorder state");
  if (r.Get<std::int32_t>() != num_samples_)
    throw InputError("checkpoint: recorder sample count differs (duration or output rate changed)");
  next_sample_ = r.Get<std::int32_t>();
  if (r.Get<std::uint64_t>() != series_.size())
    throw InputError("checkpoint: recorder outputs differ from the scene's");
  for (Series& s : series_) s.data = r.GetVector<double>();
  fine_index_ = r.Get<std::int64_t>();
  prev_t_ = r.Get<double>();
  prev_v_ = r.GetVector<double>();
  last_fine_v_ = r.GetVector<double>();
  last_fine_a_ = r.GetVector<double>();
  if (r.Get<std::uint64_t>() != decimators_.size())
    throw InputError("checkpoint: recorder sensor channels differ from the scene's");
  for (size_t c = 0; c < decimators_.size(); ++c) {
    decimators_[c].RestoreState(r.GetVector<double>());
    accel_out_[c] = r.GetVector<double>();
  }
  last_orbit_ = r.GetVector<double>();
  next_field_sample_ = r.Get<std::int32_t>();
}

}  // namespace spallkit::sim
