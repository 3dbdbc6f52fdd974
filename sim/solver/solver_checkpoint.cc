// ExplicitSolver's checkpoint: the whole time-stepping state as one binary blob
// (core/checkpoint_io.h), so that a resumed run is bit-identical to an uninterrupted one.
#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/checkpoint_io.h"
#include "core/error.h"
#include "sim/solver/explicit_solver.h"

namespace spallkit::sim::solver {
namespace {
// 3: the last step's nodal forces and dt_avg (energies at t^n).
constexpr char kMagic[8] = {'S', 'P', 'K', 'C', 'K', 'P', 'T', '3'};
}  // namespace

std::string ExplicitSolver::SaveState() const {
  CheckpointWriter out;
  for (char c : kMagic) out.Put(c);
  out.Put<std::uint64_t>(state_.size());
  out.Put<std::uint64_t>(elements_.num_elements());
  out.Put<std::uint64_t>(rigid_bodies_.size());
  out.Put<std::uint64_t>(contributors_.size());
  out.Put(initialized_);
  for (double v : {time_, dt_, dt_prev_, next_output_time_, last_dt_avg_}) out.Put(v);
  out.Put(step_), out.Put(last_output_step_);
  for (double v : {damping_work_, reaction_work_, load_work_, initial_kinetic_, initial_stored_})
    out.Put(v);
  for (const auto* v : {&state_.x, &state_.y, &state_.vx, &state_.vy, &state_.fx, &state_.fy})
    out.PutVector(*v);
  elements_.Save(&out);
  for (const auto& st : rigid_states_) out.Put(st);
  for (const ForceContributor* c : contributors_) {
    out.PutBytes(c->Name());
    out.PutBytes(c->SaveState());
  }
  return out.Take();
}

void ExplicitSolver::LoadState(std::string_view bytes) {
  if (bytes.size() < sizeof kMagic || !std::equal(kMagic, kMagic + sizeof kMagic, bytes.data()))
    throw InputError("not a spallkit solver checkpoint");
  CheckpointReader in(bytes.substr(sizeof kMagic), "checkpoint");
  if (in.Get<std::uint64_t>() != state_.size() ||
      in.Get<std::uint64_t>() != static_cast<std::uint64_t>(elements_.num_elements()) ||
      in.Get<std::uint64_t>() != rigid_bodies_.size() ||
      in.Get<std::uint64_t>() != contributors_.size())
    throw InputError(
        "checkpoint: model size (nodes, elements, rigid bodies or contributors) differs");
  in.Get<bool>();  // initialized_ when saved: a loaded solver is initialised here either way
  if (!initialized_) {
    // Set up scratch, damping constants and threads without calling the t = 0 output.
    auto cb = std::move(callback_);
    callback_ = nullptr;
    Initialize();
    callback_ = std::move(cb);
  }
  for (double* v : {&time_, &dt_, &dt_prev_, &next_output_time_, &last_dt_avg_})
    *v = in.Get<double>();
  step_ = in.Get<long>(), last_output_step_ = in.Get<long>();
  for (double* v :
       {&damping_work_, &reaction_work_, &load_work_, &initial_kinetic_, &initial_stored_})
    *v = in.Get<double>();
  in.GetVectorInto(&state_.x, "x"), in.GetVectorInto(&state_.y, "y");
  in.GetVectorInto(&state_.vx, "vx"), in.GetVectorInto(&state_.vy, "vy");
  in.GetVectorInto(&state_.fx, "fx"), in.GetVectorInto(&state_.fy, "fy");
  elements_.Load(&in);
  for (auto& st : rigid_states_) st = in.Get<RigidBodyState>();
  for (ForceContributor* c : contributors_) {
    const std::string name = in.GetBytes();
    const std::string blob = in.GetBytes();
    if (name != c->Name())
      throw InputError("checkpoint: contributor '" + name + "' where '" + c->Name() +
                       "' was expected");
    c->LoadState(blob);
  }
}

void ExplicitSolver::SaveCheckpoint(const std::string& path) const {
  WriteFileAtomically(path, SaveState());
}

void ExplicitSolver::LoadCheckpoint(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open checkpoint");
  std::ostringstream bytes;
  bytes << file.rdbuf();
  try {
    LoadState(bytes.str());
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
}

}  // namespace spallkit::sim::solver
