#include "sim/bearing/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/checkpoint_io.h"
#include "core/error.h"
#include "core/hdf5.h"
#include "core/record_io.h"
#include "sim/bearing/fidelity_choice.h"

namespace spallkit::sim {
namespace {

// Format 02: magic, the writing spallkit's version, the effective scene, the model's and the
// recorder's state. 01 (no version) was written by older builds.
constexpr char kMagic[8] = {'S', 'P', 'K', 'S', 'I', 'M', '0', '2'};
constexpr char kMagicFormat01[8] = {'S', 'P', 'K', 'S', 'I', 'M', '0', '1'};
constexpr char kStartAgain[] = "; run again without --resume";

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open checkpoint");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

}  // namespace

std::string SimulationSummary::BriefReport() const {
  std::ostringstream os;
  os.precision(4);
  os << (completed ? "completed" : "stopped") << " at t = " << time * 1e3 << " ms";
  if (resumed) os << " (resumed from " << resumed_from_s * 1e3 << " ms)";
  os << "\nsteps " << steps << " (" << steps_this_run << " this run), time step "
     << min_time_step * 1e9 << " .. " << max_time_step * 1e9 << " ns, " << elements << " elements, "
     << threads << " thread(s)";
  os << "\nwall time " << wall_seconds << " s, " << ns_per_element_cycle << " ns per element-cycle";
  if (std::isfinite(energy_balance_error))
    os << "\nenergy balance error " << energy_balance_error * 100 << " %, hourglass/internal "
       << hourglass_to_internal * 100 << " %";
  else
    os << "\nenergy books not kept (no \"energy\" output and solver.max_energy_error_percent "
          "= 0)";
  if (cage_omega_theory != 0.0)
    os << "\ncage " << cage_omega_mean << " rad/s (theory " << cage_omega_theory
       << "), slip ratio S = " << cage_slip_mean * 100 << " %, centre " << cage_offset_mean * 1e3
       << " mm off the bearing's (radial play " << cage_radial_play * 1e3 << " mm)";
  return os.str();
}

Simulation::Simulation(const Scene& scene, SimulationOptions options)
    : options_(std::move(options)) {
  FidelityChoice choice;
  // Skip what is not needed: every model keeps its per-step energy terms (the FE solver's and
  // the rigid rollers') only when the energy output, the energy guard or the ledger reads them.
  BearingModelOptions model_options = options_.model;
  const bool energy_read = Asks(scene.outputs, Output::kEnergy) ||
                           scene.solver.max_energy_error_percent > 0.0 ||
                           model_options.track_contributor_work;
  if (!energy_read) model_options.hybrid.energy_books = model_options.energy_books = false;
  model_ = MakeBearingModel(WithChosenFidelity(scene, &choice), model_options);
  fidelity_reason_ = choice.reason;
  RecorderOptions ro;
  ro.output_rate_hz = scene.run.output_rate_hz;
  ro.field_rate_hz = scene.run.field_rate_hz;
  ro.duration_s = scene.run.duration_s;
  ro.outputs = scene.outputs;
  ro.fine_factor = options_.fine_factor;
  recorder_ = std::make_unique<Recorder>(*model_, ro);
  Recorder* rec = recorder_.get();
  model_->SetObserver([rec] { rec->Observe(); });
  if (options_.checkpoint_path.empty() && !options_.output_path.empty())
    options_.checkpoint_path = options_.output_path + ".ckpt";
}

void Simulation::SaveCheckpoint(const std::string& path) const {
  CheckpointWriter out;
  for (char c : kMagic) out.Put(c);
  out.PutBytes(SPALLKIT_VERSION);
  out.PutBytes(model_->scene().effective_toml);
  out.PutBytes(model_->SaveState());
  out.PutBytes(recorder_->SaveState());
  WriteFileAtomically(path, out.bytes());
}

void Simulation::LoadCheckpoint(const std::string& path) {
  const std::string s = ReadAll(path);
  if (s.size() >= sizeof kMagicFormat01 &&
      std::memcmp(s.data(), kMagicFormat01, sizeof kMagicFormat01) == 0)
    throw InputError(path + ": checkpoint written by an older spallkit (format 01)" + kStartAgain);
  if (s.size() < sizeof kMagic || std::memcmp(s.data(), kMagic, sizeof kMagic) != 0)
    throw InputError(path + ": not a spall simulate checkpoint");
  CheckpointReader in(std::string_view(s).substr(sizeof kMagic), path + ": checkpoint");
  const std::string version = in.GetBytes();
  if (in.GetBytes() != model_->scene().effective_toml)
    throw InputError(path + ": checkpoint was written for a different scene (or --set values)");
  const std::string model_blob = in.GetBytes();
  const std::string recorder_blob = in.GetBytes();
  try {
    model_->LoadState(model_blob);
    recorder_->LoadState(recorder_blob);
  } catch (const InputError& e) {
    // The state layouts change between builds; say whose checkpoint it was.
    const std::string writer =
        version == SPALLKIT_VERSION ? "" : " (written by spallkit " + version + ")";
    throw InputError(path + ": " + e.what() + writer + kStartAgain);
  }
}

SimulationSummary Simulation::Run() {
  const Scene& scene = model_->scene();
  BearingModel& model = *model_;
  const double duration = scene.run.duration_s;
  const double ci = scene.solver.checkpoint_interval_s;
  SimulationSummary sum;
  if ((ci > 0 || options_.resume || std::isfinite(options_.stop_after_s)) &&
      options_.checkpoint_path.empty())
    throw InputError("simulate: checkpoints need an output file (-o)");
  if (options_.resume) {
    LoadCheckpoint(options_.checkpoint_path);
    sum.resumed = true;
    sum.resumed_from_s = model.time();
  }
  const double progress_dt =
      options_.progress_interval_s > 0 ? options_.progress_interval_s : duration / 200.0;
  sum.min_time_step = std::numeric_limits<double>::infinity();
  const long first_step = model.step();
  const double start_time = model.time();
  double next_ckpt = ci > 0 ? (std::floor(model.time() / ci + 1e-12) + 1.0) * ci
                            : std::numeric_limits<double>::infinity();
  const auto t0 = std::chrono::steady_clock::now();
  bool stopped = false;
  while (model.time() < duration) {
    const double next_progress = (std::floor(model.time() / progress_dt) + 1.0) * progress_dt;
    const double target = std::min({duration, next_ckpt, next_progress, options_.stop_after_s});
    const solver::SolverSummary s = model.Run(target);
    if (s.steps > 0) {
      sum.min_time_step = std::min(sum.min_time_step, s.min_time_step);
      sum.max_time_step = std::max(sum.max_time_step, s.max_time_step);
    }
    sum.threads = s.threads;
    CheckEnergyBalance();
    const bool stop_now = model.time() >= options_.stop_after_s && model.time() < duration;
    if (model.time() >= next_ckpt || stop_now) {
      if (model.time() < duration) SaveCheckpoint(options_.checkpoint_path);
      while (next_ckpt <= model.time()) next_ckpt += ci;
    }
    if (options_.progress) {
      SimulationProgress p;
      p.time = model.time(), p.duration = duration, p.steps = model.step();
      p.time_step = model.time_step();
      p.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      p.start_time = start_time;
      options_.progress(p);
    }
    if (stop_now) {
      stopped = true;
      break;
    }
  }
  sum.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sum.time = model.time();
  sum.steps = model.step();
  sum.steps_this_run = model.step() - first_step;
  if (sum.steps_this_run == 0) sum.min_time_step = sum.max_time_step = model.time_step();
  sum.elements = model_->num_elements();
  sum.nodes = model_->num_nodes();
  if (sum.steps_this_run > 0 && sum.elements > 0)
    sum.ns_per_element_cycle =
        1e9 * sum.wall_seconds / (static_cast<double>(sum.steps_this_run) * sum.elements);
  sum.energies = model.energies();
  sum.energy_balance_error = sum.energies.BalanceError();
  sum.ledger = model.ContributorLedgers();
  sum.hourglass_to_internal =
      sum.energies.internal > 0 ? sum.energies.hourglass / sum.energies.internal : 0.0;
  // The "cage" output records /cage/omega and /cage/centre (x, y) together, sample by sample.
  const Recorder::Series* w = recorder_->Find("/cage/omega");
  const Recorder::Series* c = recorder_->Find("/cage/centre");
  if (w && c) {
    const auto& t = recorder_->Find("/time")->data;
    double t_from = 2.0 * scene.operation.ramp_s;
    if (t.empty() || t.back() < t_from) t_from = t.empty() ? 0.0 : 0.5 * t.back();
    double omega = 0.0, offset = 0.0;
    int n = 0;
    for (size_t i = 0; i < t.size() && i < w->data.size(); ++i)
      if (t[i] >= t_from)
        omega += w->data[i], offset += std::hypot(c->data[2 * i], c->data[2 * i + 1]), ++n;
    if (n > 0) {
      sum.cage_omega_mean = omega / n;
      sum.cage_omega_theory = model_->TheoreticalCageSpeed(duration);
      sum.cage_slip_mean = sum.cage_omega_mean / sum.cage_omega_theory - 1.0;
      sum.cage_offset_mean = offset / n;
      sum.cage_radial_play = model_->options().cage_guide.radial_play_m;
    }
  }
  if (stopped) return sum;
  recorder_->Finish();
  sum.completed = true;
  WriteOutputs(sum);
  if (!options_.checkpoint_path.empty()) std::remove(options_.checkpoint_path.c_str());
  return sum;
}

// A run whose energy books do not balance has gone wrong numerically (e.g. a full-FE cage without
// its pocket guide, docs/BEARING_MODEL.md, "Speed range of the full-FE section"): stop it instead
// of writing plausible-looking signals. Energies below a millijoule (start of the ramp) are not
// judged. With the work ledger on, the message names the worst account.
void Simulation::CheckEnergyBalance() const {
  const double limit = model_->scene().solver.max_energy_error_percent;
  if (limit <= 0.0) return;
  const solver::Energies e = model_->energies();
  const double error = 100.0 * e.BalanceError();
  if (e.Scale() < 1e-3 || error <= limit) return;
  std::ostringstream os;
  os.precision(3);
  os << "simulate: energy balance error " << error << " % at t = " << 1e3 * model_->time()
     << " ms exceeds solver.max_energy_error_percent = " << limit
     << "; the results would not be trustworthy and were not written (spall simulate "
        "--energy-ledger names the contact pair or constraint that breaks the balance)";
  // With the work ledger: name the contributor whose books are furthest off.
  const std::vector<solver::ContributorLedger> ledger = model_->ContributorLedgers();
  const auto worst =
      std::max_element(ledger.begin(), ledger.end(), [](const auto& a, const auto& b) {
        return std::abs(a.Created()) < std::abs(b.Created());
      });
  if (worst != ledger.end())
    os << "; most energy created by '" << worst->name << "': " << worst->Created() << " J";
  throw NumericalError(os.str());
}

void Simulation::WriteOutputs(const SimulationSummary& summary) const {
  if (!options_.output_path.empty()) {
    AtomicFile out(options_.output_path);
    {
      h5::File f = h5::File::Create(out.temp_path());
      f.SetAttribute("/", "spallkit_version", SPALLKIT_VERSION);
      f.SetAttribute("/", "scene", model_->scene().effective_toml);
      f.SetAttribute("/", "mesh_quality", model_->mesh_quality().Report());
      f.SetAttribute("/", "steps", static_cast<double>(summary.steps));
      f.SetAttribute("/", "fidelity", std::string(FidelityName(model_->fidelity())));
      f.SetAttribute("/", "fidelity_reason", fidelity_reason_);
      f.SetAttribute("/", "energy_balance_error", summary.energy_balance_error);
      recorder_->Write(&f);
      f.Close();
    }
    out.Commit();
  }
  if (!options_.csv_path.empty()) {
    const auto& channels = model_->sensor_channels();
    std::vector<std::pair<std::string, std::vector<double>>> cols;
    cols.emplace_back("time (s)", recorder_->Find("/time")->data);
    bool y = false, x = false;
    for (size_t c = 0; c < channels.size(); ++c) {
      if (channels[c].direction == Axis::kY && !y)
        cols.emplace_back("accel_y (m/s^2)", recorder_->Acceleration(static_cast<int>(c))),
            y = true;
      if (channels[c].direction == Axis::kX && !x)
        cols.emplace_back("accel_z (m/s^2)", recorder_->Acceleration(static_cast<int>(c))),
            x = true;
    }
    if (cols.size() < 2)
      throw InputError("simulate: --csv needs the 'acceleration' output and at least one sensor");
    spallkit::WriteCsvRecord(options_.csv_path, cols);
  }
}

}  // namespace spallkit::sim
