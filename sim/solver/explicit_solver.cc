#include "sim/solver/explicit_solver.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <sstream>
#include <type_traits>

#include "core/atomic_file.h"
#include "core/constants.h"
#include "core/error.h"

namespace spallkit::sim::solver {
namespace {

constexpr int kNodeChunk = 1024;  // fixed node chunk: sums do not depend on the thread count
constexpr int kRigidSums = 7;     // m, mx, my, mvx, mvy, m(x vy - y vx), m(x^2 + y^2)
constexpr int kMinElementsPerThread = 10000;

}  // namespace

TimeFunction RampedRotation(double omega, double ramp_time) {
  return [omega, ramp_time](double t) {
    if (t <= 0.0) return 0.0;
    if (t < ramp_time) return omega * t * t / (2.0 * ramp_time);
    return omega * (t - 0.5 * ramp_time);
  };
}

TimeFunction RampedSpeed(double omega, double ramp_time) {
  return [omega, ramp_time](double t) {
    if (t <= 0.0) return 0.0;
    return t < ramp_time ? omega * t / ramp_time : omega;
  };
}

TimeFunction LinearRamp(double value, double ramp_time) {
  return [value, ramp_time](double t) {
    return ramp_time > 0.0 && t < ramp_time ? value * std::max(t, 0.0) / ramp_time : value;
  };
}

bool SolverOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* m) {
    if (error) *error = m;
    return false;
  };
  if (!(time_step_scale > 0.0 && time_step_scale <= 1.0))
    return fail("solver: time_step_scale must be in (0, 1]");
  if (!(max_time_step > 0.0)) return fail("solver: max_time_step must be > 0");
  if (!(mass_damping_ratio >= 0.0)) return fail("solver: mass_damping_ratio must be >= 0");
  if (mass_damping_ratio > 0.0 && !(damping_frequency > 0.0))
    return fail("solver: damping_frequency (Hz) must be > 0 when mass_damping_ratio > 0");
  if (!(stiffness_damping_ratio >= 0.0))
    return fail("solver: stiffness_damping_ratio must be >= 0");
  if (stiffness_damping_ratio > 0.0 && !(stiffness_damping_frequency > 0.0))
    return fail(
        "solver: stiffness_damping_frequency (Hz) must be > 0 when stiffness_damping_ratio > 0");
  if (output_every_steps < 0) return fail("solver: output_every_steps must be >= 0");
  if (!(output_interval >= 0.0)) return fail("solver: output_interval must be >= 0");
  if (!(max_energy_error >= 0.0)) return fail("solver: max_energy_error must be >= 0");
  if (num_threads < 0) return fail("solver: num_threads must be >= 0");
  if (!energy_terms && max_energy_error > 0.0)
    return fail("solver: max_energy_error needs energy_terms (the balance is not kept without)");
  if (!energy_terms && track_contributor_work)
    return fail("solver: track_contributor_work needs energy_terms");
  return true;
}

std::string SolverSummary::BriefReport() const {
  char buf[512];
  std::snprintf(
      buf,
      sizeof buf,
      "steps %ld, t = %.6g s, dt %.4g..%.4g s, %d thread(s), %.3f s wall, %.2f ns/element-cycle; "
      "E_kin %.4g J, E_int %.4g J, E_hg %.4g J, E_damp %.4g J, W_ext %.4g J, balance error %.3g",
      steps,
      time,
      min_time_step,
      max_time_step,
      threads,
      wall_seconds,
      ns_per_element_cycle,
      energies.kinetic,
      energies.internal,
      energies.hourglass,
      energies.damping,
      energies.external,
      energies.BalanceError());
  return buf;
}

ExplicitSolver::ExplicitSolver(const fe::Mesh& mesh,
                               std::vector<fe::Section> sections,
                               SolverOptions options)
    : elements_(mesh, std::move(sections)), options_(options) {
  std::string err;
  if (!options_.IsValid(&err)) throw InputError(err);
  const int nn = mesh.num_nodes();
  state_.Resize(nn);
  state_.x0 = mesh.x, state_.y0 = mesh.y, state_.x = mesh.x, state_.y = mesh.y;
  elements_.AddLumpedMass(&state_);
  elements_.set_energy_terms(options_.energy_terms);
  node_part_.assign(nn, -1);
  for (int e = mesh.num_elements() - 1; e >= 0; --e)
    for (int id : mesh.quads[e]) node_part_[id] = mesh.element_part[e];
  for (int i = 0; i < nn; ++i)
    if (!(state_.mass[i] > 0.0)) {
      std::ostringstream os;
      os << "solver: node " << i << " belongs to no element (zero mass)";
      throw InputError(os.str());
    }
  constrained_.assign(nn, 0);
  part_rigid_.assign(5 * static_cast<size_t>(mesh.num_parts()), 0.0);
  const int nchunks = (nn + kNodeChunk - 1) / kNodeChunk;
  chunk_sums_.assign(static_cast<size_t>(nchunks) * mesh.num_parts() * kRigidSums, 0.0);
}

void ExplicitSolver::AddContributor(ForceContributor* c) {
  SPALLKIT_CHECK(c != nullptr, "null contributor");
  SPALLKIT_CHECK(!initialized_, "add contributors before the first step");
  contributors_.push_back(c);
}

int ExplicitSolver::AddRigidBody(RigidBody body) {
  SPALLKIT_CHECK(!initialized_, "add constraints before the first step");
  for (int id : body.nodes) {
    if (id < 0 || id >= static_cast<int>(state_.size()))
      throw InputError("rigid body '" + body.name + "': node id out of range");
    if (constrained_[id])
      throw InputError("rigid body '" + body.name + "': node already constrained");
    constrained_[id] = 1;
  }
  if (!(body.extra_mass >= 0.0))
    throw InputError("rigid body '" + body.name + "': extra_mass must be >= 0");
  rigid_bodies_.push_back(std::move(body));
  RigidBodyState st;
  st.x = rigid_bodies_.back().ref_x, st.y = rigid_bodies_.back().ref_y;
  rigid_states_.push_back(st);
  return static_cast<int>(rigid_bodies_.size()) - 1;
}

void ExplicitSolver::AddVelocityCondition(VelocityCondition c) {
  SPALLKIT_CHECK(!initialized_, "add constraints before the first step");
  if (c.vx.size() != c.nodes.size() || c.vy.size() != c.nodes.size())
    throw InputError("velocity condition: vx and vy need one value per node");
  for (int id : c.nodes) {
    if (id < 0 || id >= static_cast<int>(state_.size()))
      throw InputError("velocity condition: node id out of range");
    if (constrained_[id] == 1) throw InputError("velocity condition: node already in a rigid body");
    constrained_[id] = 2;
  }
  velocity_conditions_.push_back(std::move(c));
}

void ExplicitSolver::FixNodes(const std::vector<int>& nodes, bool fix_x, bool fix_y) {
  VelocityCondition c;
  c.nodes = nodes;
  c.vx.assign(nodes.size(), 0.0);
  c.vy.assign(nodes.size(), 0.0);
  c.fix_x = fix_x, c.fix_y = fix_y;
  AddVelocityCondition(std::move(c));
}

void ExplicitSolver::SetRigidVelocity(
    const std::vector<int>& nodes, double vx, double vy, double omega, double cx, double cy) {
  for (int id : nodes) {
    state_.vx[id] = vx - omega * (state_.y[id] - cy);
    state_.vy[id] = vy + omega * (state_.x[id] - cx);
  }
}

void ExplicitSolver::Initialize() {
  // Default: OpenMP's thread count, but one thread for small models, where the two
  // fork/join barriers per step cost more than the work (and much more on a busy machine).
  threads_ = options_.num_threads > 0 ? options_.num_threads
             : elements_.num_elements() < kMinElementsPerThread
                 ? 1
                 : std::min(omp_get_max_threads(),
                            std::max(1, elements_.num_elements() / kMinElementsPerThread));
  split_contributors_ = 0;  // contributors are fixed from here on (AddContributor checks)
  while (split_contributors_ < static_cast<int>(contributors_.size()) &&
         contributors_[split_contributors_]->SplitsForces())
    ++split_contributors_;
  mass_damping_ = 4.0 * kPi * options_.mass_damping_ratio * options_.damping_frequency;
  if (options_.stiffness_damping_ratio > 0.0)
    elements_.set_stiffness_damping(options_.stiffness_damping_ratio /
                                    (kPi * options_.stiffness_damping_frequency));
  for (auto* v : {&old_vx_, &old_vy_, &old_x_, &old_y_})
    v->assign(state_.size(), 0.0);  // constrained nodes only
  // Here rather than in the constructor: state().mass may be edited before the first step.
  inv_mass_.resize(state_.size());
  for (size_t i = 0; i < state_.size(); ++i) inv_mass_[i] = 1.0 / state_.mass[i];
  // Rigid bodies start with the momentum-weighted velocity of their nodes.
  for (size_t b = 0; b < rigid_bodies_.size(); ++b) {
    double m = 0, px = 0, py = 0;
    for (int id : rigid_bodies_[b].nodes)
      m += state_.mass[id], px += state_.mass[id] * state_.vx[id],
          py += state_.mass[id] * state_.vy[id];
    if (m > 0) rigid_states_[b].vx = px / m, rigid_states_[b].vy = py / m;
    if (rigid_bodies_[b].angle) rigid_states_[b].angle = rigid_bodies_[b].angle(0.0);
  }
  double ke = 0.0;
  for (size_t i = 0; i < state_.size(); ++i)
    ke += 0.5 * state_.mass[i] * (state_.vx[i] * state_.vx[i] + state_.vy[i] * state_.vy[i]);
  for (size_t b = 0; b < rigid_bodies_.size(); ++b)
    ke += 0.5 * rigid_bodies_[b].extra_mass *
          (rigid_states_[b].vx * rigid_states_[b].vx + rigid_states_[b].vy * rigid_states_[b].vy);
  initial_kinetic_ = ke;
  initialized_ = true;
  next_output_time_ = options_.output_interval;
  if (callback_) callback_(*this);
  last_output_step_ = 0;
}

void ExplicitSolver::RigidMotionSums(int c) {
  const int nn = static_cast<int>(state_.size()), np = elements_.num_parts();
  double* sums = &chunk_sums_[static_cast<size_t>(c) * np * kRigidSums];
  std::fill(sums, sums + np * kRigidSums, 0.0);
  const int end = std::min(nn, (c + 1) * kNodeChunk);
  const double* __restrict ms = state_.mass.data();
  const double* __restrict xs = state_.x.data();
  const double* __restrict ys = state_.y.data();
  const double* __restrict us = state_.vx.data();
  const double* __restrict ws = state_.vy.data();
  // Runs of nodes of one part, summed in registers (vectorised), then added to the part's sums.
  for (int i = c * kNodeChunk; i < end;) {
    const int part = node_part_[i];
    int j = i + 1;
    while (j < end && node_part_[j] == part) ++j;
    double t0 = 0, t1 = 0, t2 = 0, t3 = 0, t4 = 0, t5 = 0, t6 = 0;
#pragma omp simd reduction(+ : t0, t1, t2, t3, t4, t5, t6)
    for (int k = i; k < j; ++k) {
      const double m = ms[k], x = xs[k], y = ys[k], vx = us[k], vy = ws[k];
      t0 += m, t1 += m * x, t2 += m * y, t3 += m * vx, t4 += m * vy;
      t5 += m * (x * vy - y * vx), t6 += m * (x * x + y * y);
    }
    double* s = sums + part * kRigidSums;
    s[0] += t0, s[1] += t1, s[2] += t2, s[3] += t3, s[4] += t4, s[5] += t5, s[6] += t6;
    i = j;
  }
}

void ExplicitSolver::ReducePartRigidMotion() {
  const int nn = static_cast<int>(state_.size()), np = elements_.num_parts();
  const int nchunks = (nn + kNodeChunk - 1) / kNodeChunk;
  for (int p = 0; p < np; ++p) {
    double t[kRigidSums] = {0, 0, 0, 0, 0, 0, 0};
    for (int c = 0; c < nchunks; ++c)
      for (int k = 0; k < kRigidSums; ++k)
        t[k] += chunk_sums_[(static_cast<size_t>(c) * np + p) * kRigidSums + k];
    double* r = &part_rigid_[5 * static_cast<size_t>(p)];
    if (!(t[0] > 0.0)) {
      std::fill(r, r + 5, 0.0);
      continue;
    }
    const double cx = t[1] / t[0], cy = t[2] / t[0], vx = t[3] / t[0], vy = t[4] / t[0];
    const double lz = t[5] - t[0] * (cx * vy - cy * vx);
    const double j = t[6] - t[0] * (cx * cx + cy * cy);
    r[0] = vx, r[1] = vy, r[2] = j > 0.0 ? lz / j : 0.0, r[3] = cx, r[4] = cy;
  }
}

void ExplicitSolver::PartRigidMotion(int part, double* vx, double* vy, double* omega) const {
  // Recomputed from the current velocities (cheap, serial, for callers and tests).
  double t[kRigidSums] = {0, 0, 0, 0, 0, 0, 0};
  for (size_t i = 0; i < state_.size(); ++i) {
    if (node_part_[i] != part) continue;
    const double m = state_.mass[i], x = state_.x[i], y = state_.y[i], u = state_.vx[i],
                 w = state_.vy[i];
    t[0] += m, t[1] += m * x, t[2] += m * y, t[3] += m * u, t[4] += m * w,
        t[5] += m * (x * w - y * u), t[6] += m * (x * x + y * y);
  }
  const double cx = t[1] / t[0], cy = t[2] / t[0];
  *vx = t[3] / t[0], *vy = t[4] / t[0];
  *omega = (t[5] - t[0] * (cx * *vy - cy * *vx)) / (t[6] - t[0] * (cx * cx + cy * cy));
}

// Body of the element pass's parallel region (orphaned work-sharing constructs: called inside a
// team it splits the work, called directly it runs on one thread without an OpenMP region,
// which libgomp would otherwise allocate a team for every time when it has no thread pool).
void ExplicitSolver::ElementPass(double h, bool rigid_sums, bool gather) {
  const int nn = static_cast<int>(state_.size());
  const int nchunks = (nn + kNodeChunk - 1) / kNodeChunk;
  const int nblocks = elements_.num_blocks();
  constexpr int kGather = fe::QuadElements::kGatherChunk;
  const int ngather = (nn + kGather - 1) / kGather;
#pragma omp for schedule(static) nowait
  for (int k = 0; k < nblocks; ++k) elements_.ComputeBlock(k, state_, h);
  if (rigid_sums) {
    // Rigid motion of the parts from x^n, v^(n-1/2) (read-only here, so no barrier needed).
#pragma omp for schedule(static) nowait
    for (int c = 0; c < nchunks; ++c) RigidMotionSums(c);
  }
  if (gather) {
#pragma omp barrier
#pragma omp for schedule(static) nowait
    for (int c = 0; c < ngather; ++c)
      elements_.GatherForces(&state_, c * kGather, std::min(nn, (c + 1) * kGather));
  }
}

// Central-difference update of node chunk c (optionally gathering its element forces first,
// while they are hot in cache). Returns the mass-damping work of the chunk.
double ExplicitSolver::UpdateNodes(int c, bool gather, const UpdateConstants& k) {
  const int nn = static_cast<int>(state_.size());
  const int begin = c * kNodeChunk, end = std::min(nn, (c + 1) * kNodeChunk);
  if (gather) elements_.GatherForces(&state_, begin, end);
  double* __restrict x = state_.x.data();
  double* __restrict y = state_.y.data();
  double* __restrict vx = state_.vx.data();
  double* __restrict vy = state_.vy.data();
  const double* __restrict fx = state_.fx.data();
  const double* __restrict fy = state_.fy.data();
  const double* __restrict m = state_.mass.data();
  const double* __restrict inv_m = inv_mass_.data();
  const double dt = k.dt, dt_avg = k.dt_avg;
  if (!k.damp) {
#pragma omp simd
    for (int i = begin; i < end; ++i) {
      const double s = dt_avg * inv_m[i];
      vx[i] += s * fx[i], vy[i] += s * fy[i];
      x[i] += dt * vx[i], y[i] += dt * vy[i];
    }
    return 0.0;
  }
  // Semi-implicit mass damping of the velocity relative to the part's rigid motion (or of the
  // absolute velocity); written branch-free so that it vectorises.
  const double* __restrict pr = part_rigid_.data();
  const int* __restrict part = node_part_.data();
  const char* __restrict fixed = constrained_.data();
  const double c_old = k.c_old, c_inv = k.c_inv, rel = k.relative ? 1.0 : 0.0;
  const double w_scale = 0.25 * mass_damping_ * dt_avg;
  double work = 0.0;
  // Runs of nodes of one part (parts are contiguous after ReorderForLocality), so the part's
  // rigid motion is a scalar in the vector loop.
  for (int i0 = begin; i0 < end;) {
    const int p = part[i0];
    int i1 = i0 + 1;
    while (i1 < end && part[i1] == p) ++i1;
    const double* r = pr + 5 * p;
    const double r0 = rel * r[0], r1 = rel * r[1], r2 = rel * r[2], r3 = r[3], r4 = r[4];
    // One loop for both: with kWork the mass-damping work is summed (energy_terms), without it
    // the update is the same.
    auto update = [&](auto with_work) {
      constexpr bool kWork = decltype(with_work)::value;
      double run_work = 0.0;
#pragma omp simd reduction(+ : run_work)
      for (int i = i0; i < i1; ++i) {
        const double rvx = r0 - r2 * (y[i] - r4), rvy = r1 + r2 * (x[i] - r3);
        const double s = dt_avg * inv_m[i];
        const double ux0 = vx[i] - rvx, uy0 = vy[i] - rvy;
        const double ux1 = (c_old * ux0 + s * fx[i]) * c_inv;
        const double uy1 = (c_old * uy0 + s * fy[i]) * c_inv;
        const double vx1 = rvx + ux1, vy1 = rvy + uy1;
        if constexpr (kWork) {
          const double free = fixed[i] ? 0.0 : 1.0;  // constrained nodes: no damping work
          run_work +=
              free * w_scale * m[i] * ((ux0 + ux1) * (vx[i] + vx1) + (uy0 + uy1) * (vy[i] + vy1));
        }
        vx[i] = vx1, vy[i] = vy1;
        x[i] += dt * vx1, y[i] += dt * vy1;
      }
      return run_work;
    };
    const double run_work = k.energy ? update(std::true_type{}) : update(std::false_type{});
    work += run_work;
    i0 = i1;
  }
  return work;
}

void ExplicitSolver::AddContributorForces(double dt) {
  const int n = static_cast<int>(contributors_.size());
  const int split = split_contributors_;
  if (threads_ > 1 && split > 1) {
    // Dynamic: the pairs' costs differ by orders (far apart: a bounding-box test).
    std::vector<std::exception_ptr>& errors = contributor_errors_;
    errors.assign(threads_, nullptr);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads_)
    for (int i = 0; i < split; ++i) {
      try {
        contributors_[i]->ComputeForces(state_, time_, dt);
      } catch (...) {
        const int t = omp_get_thread_num();
        if (!errors[t]) errors[t] = std::current_exception();
      }
    }
    for (const auto& e : errors)
      if (e) std::rethrow_exception(e);
  } else {
    for (int i = 0; i < split; ++i) contributors_[i]->ComputeForces(state_, time_, dt);
  }
  for (int i = 0; i < split; ++i) contributors_[i]->ApplyForces(state_);
  for (int i = split; i < n; ++i) contributors_[i]->AddForces(state_, time_, dt);
}

void ExplicitSolver::Step() {
  if (!initialized_) Initialize();
  const double h = dt_prev_;
  // Element pass. With contributors the nodal forces must be complete before they run (they
  // may read them), so the gather is done in the element pass's parallel region; without, it is
  // fused into the nodal update below. The rigid-motion sums of relative mass damping run in the
  // same region. Either way: two parallel regions (sync points) per step, the minimum for a
  // global stable step, and none at all on one thread.
  const bool fuse_gather = contributors_.empty();
  const bool damp = mass_damping_ > 0.0;
  const bool relative = damp && options_.damping_relative_to_rigid_motion;
  const int nn = static_cast<int>(state_.size());
  const int nchunks = (nn + kNodeChunk - 1) / kNodeChunk;
  if (threads_ > 1) {
#pragma omp parallel num_threads(threads_)
    ElementPass(h, relative, !fuse_gather);
  } else {
    ElementPass(h, relative, !fuse_gather);
  }
  double dt = 0.0;
  try {
    dt = options_.time_step_scale * elements_.StableStep(state_);
  } catch (const NumericalError& e) {  // say when (an inverted element is found there)
    std::ostringstream os;
    os << e.what() << " at t = " << time_ << " s (step " << step_ << ")";
    throw NumericalError(os.str());
  }
  dt = std::min(dt, options_.max_time_step);
  for (ForceContributor* c : contributors_) dt = std::min(dt, c->StableTimeStep(state_));
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    std::ostringstream os;
    os << "solver: invalid time step " << dt << " at t = " << time_ << " s (step " << step_ << ")";
    throw NumericalError(os.str());
  }
  if (options_.track_contributor_work) {
    ledger_.AddForces(state_, elements_, contributors_, time_, dt);
  } else {
    AddContributorForces(dt);
  }
  if (relative) ReducePartRigidMotion();
  if (step_ == 0) {  // forces at x^0: the contributors' initial stored energy
    initial_stored_ = 0.0;
    for (const ForceContributor* c : contributors_) initial_stored_ += c->StoredEnergy();
  }

  // Remember v^(n-1/2) of constrained nodes (reaction work).
  auto remember = [&](int id) {
    old_vx_[id] = state_.vx[id], old_vy_[id] = state_.vy[id], old_x_[id] = state_.x[id],
    old_y_[id] = state_.y[id];
  };
  for (const auto& b : rigid_bodies_)
    for (int id : b.nodes) remember(id);
  for (const auto& c : velocity_conditions_)
    for (int id : c.nodes) remember(id);

  UpdateConstants k;
  k.dt = dt;
  k.dt_avg = 0.5 * (h + dt);
  const double ad = mass_damping_ * k.dt_avg * 0.5;
  k.c_old = 1.0 - ad, k.c_inv = 1.0 / (1.0 + ad);
  k.damp = damp, k.relative = relative, k.energy = options_.energy_terms;
  double* chunk_work = chunk_sums_.data();  // reuse scratch: one value per chunk
  if (threads_ > 1) {
#pragma omp parallel for schedule(static) num_threads(threads_)
    for (int c = 0; c < nchunks; ++c) chunk_work[c] = UpdateNodes(c, fuse_gather, k);
  } else {
    for (int c = 0; c < nchunks; ++c) chunk_work[c] = UpdateNodes(c, fuse_gather, k);
  }
  if (damp)
    for (int c = 0; c < nchunks; ++c) damping_work_ += chunk_work[c];
  const double dt_avg = k.dt_avg;
  // energies() takes the kinetic energy at t^n from v^(n+1/2) and f^n: m (v^(n+1/2) - v^(n-1/2))
  // = dt_avg f^n. The first step starts with half a step from v^0; it is a full step from
  // v^(-1/2) = v^0 - dt/2 a^0, so the measure's kinetic energy at t^0 is 1/2 m v^(-1/2) .
  // v^(1/2) = 1/2 m (v^0)^2 - 1/2 m (dt/2 a^0)^2: the reference the balance starts from (a
  // step load's first step would otherwise show as created energy).
  last_dt_avg_ = h > 0.0 ? dt_avg : dt;
  if (h == 0.0 && step_ == 0) {
    double start = 0.0;
    for (int i = 0; i < nn; ++i)  // constrained nodes: their reactions' books hold it
      if (!constrained_[i])
        start += (state_.fx[i] * state_.fx[i] + state_.fy[i] * state_.fy[i]) * inv_mass_[i];
    initial_kinetic_ -= 0.5 * dt_avg * dt_avg * start;
  }

  ApplyConstraints(dt, dt_avg, time_ + 0.5 * dt, time_ + dt);
  if (options_.track_contributor_work) ledger_.BookWork(state_, dt_avg);
  time_ += dt;
  dt_prev_ = dt;
  dt_ = dt;
  ++step_;
  MaybeOutput(false);
}

void ExplicitSolver::ApplyConstraints(double dt, double dt_avg, double t_half, double t_next) {
  fe::NodalState& s = state_;
  const bool books = options_.energy_terms;
  auto node_work = [&](int id) {  // work of the constraint on node id over the step
    if (!books) return 0.0;
    const double m = s.mass[id];
    const double ke = 0.5 * m *
                      (s.vx[id] * s.vx[id] + s.vy[id] * s.vy[id] - old_vx_[id] * old_vx_[id] -
                       old_vy_[id] * old_vy_[id]);
    return ke - dt_avg * 0.5 *
                    (s.fx[id] * (s.vx[id] + old_vx_[id]) + s.fy[id] * (s.vy[id] + old_vy_[id]));
  };
  for (size_t b = 0; b < rigid_bodies_.size(); ++b) {
    const RigidBody& body = rigid_bodies_[b];
    RigidBodyState& st = rigid_states_[b];
    double mass = body.extra_mass, fx = 0.0, fy = 0.0;
    for (int id : body.nodes) mass += s.mass[id], fx += s.fx[id], fy += s.fy[id];
    const double ax = body.force_x ? body.force_x(time_) : 0.0;
    const double ay = body.force_y ? body.force_y(time_) : 0.0;
    const double vx0 = st.vx, vy0 = st.vy;
    // One translation direction: prescribed (position, chord velocity, the reaction that moves
    // the body so) or free (Newton on the nodal and applied forces).
    auto translate = [&](const TimeFunction& motion,
                         double ref,
                         double force,
                         double applied,
                         double* x,
                         double* v,
                         double* reaction) {
      const double x0 = *x, v0 = *v;
      if (motion) {
        *x = ref + motion(t_next);
        *v = (*x - x0) / dt;
        *reaction = mass * (*v - v0) / dt_avg - force - applied;
      } else {
        *v = v0 + dt_avg * (force + applied) / mass;
        *x = x0 + dt * *v;
        *reaction = 0.0;
      }
    };
    translate(body.x_motion, body.ref_x, fx, ax, &st.x, &st.vx, &st.reaction_x);
    translate(body.y_motion, body.ref_y, fy, ay, &st.y, &st.vy, &st.reaction_y);
    st.angle = body.angle ? body.angle(t_next) : 0.0;
    const double c = std::cos(st.angle), sn = std::sin(st.angle);
    double work = 0.0;
    for (int id : body.nodes) {
      const double rx = s.x0[id] - body.ref_x, ry = s.y0[id] - body.ref_y;
      const double tx = st.x + c * rx - sn * ry, ty = st.y + sn * rx + c * ry;
      s.vx[id] = (tx - old_x_[id]) / dt;
      s.vy[id] = (ty - old_y_[id]) / dt;
      s.x[id] = tx, s.y[id] = ty;
      work += node_work(id);
    }
    work += 0.5 * body.extra_mass * (st.vx * st.vx + st.vy * st.vy - vx0 * vx0 - vy0 * vy0);
    const double wl = dt_avg * 0.5 * (ax * (st.vx + vx0) + ay * (st.vy + vy0));
    load_work_ += wl;
    reaction_work_ += work - wl;
  }
  for (const auto& vc : velocity_conditions_) {
    const double sc = vc.scale ? vc.scale(t_half) : 1.0;
    for (size_t k = 0; k < vc.nodes.size(); ++k) {
      const int id = vc.nodes[k];
      if (vc.fix_x) {
        s.vx[id] = sc * vc.vx[k];
        s.x[id] = old_x_[id] + dt * s.vx[id];
      }
      if (vc.fix_y) {
        s.vy[id] = sc * vc.vy[k];
        s.y[id] = old_y_[id] + dt * s.vy[id];
      }
      reaction_work_ += node_work(id);
    }
  }
}

void ExplicitSolver::MaybeOutput(bool force) {
  bool due = force;
  if (options_.output_every_steps > 0 && step_ % options_.output_every_steps == 0) due = true;
  if (options_.output_interval > 0.0 && time_ >= next_output_time_) {
    due = true;
    while (next_output_time_ <= time_) next_output_time_ += options_.output_interval;
  }
  if (!due || last_output_step_ == step_) return;
  last_output_step_ = step_;
  if (options_.max_energy_error > 0.0) {
    const Energies e = energies();
    if (e.Scale() > options_.energy_check_floor && e.BalanceError() > options_.max_energy_error) {
      std::ostringstream os;
      os << "solver: energy balance error " << e.BalanceError() << " exceeds "
         << options_.max_energy_error << " at t = " << time_ << " s (step " << step_ << ")";
      throw NumericalError(os.str());
    }
  }
  if (callback_) callback_(*this);
}

std::vector<ContributorLedger> ExplicitSolver::ContributorLedgers() const {
  return ledger_.Ledgers(elements_, contributors_);
}

Energies ExplicitSolver::energies() const {
  Energies e;
  const int nn = static_cast<int>(state_.size());
  const int nchunks = (nn + kNodeChunk - 1) / kNodeChunk;
  // The books are at t^n: stored energies at x^n, work up to t^n. The kinetic energy there is
  // 1/2 m v^(n+1/2)^2 less the last half step of the work of the nodal forces f^n (elements
  // and contributors; state_.fx still holds them): 1/2 dt_avg f^n . v^(n+1/2). Every other
  // force's work (applied loads, reactions, damping) is booked up to t^(n+1/2) and its half
  // step cancels against theirs; what is left is the half step of the conservative forces,
  // whose energy is stored at x^n. Measured at v^(n+1/2) instead, the balance is off by that
  // half step of their power, first order in dt and largest at impacts.
  for (int c = 0; c < nchunks; ++c) {
    double k = 0.0, power = 0.0;
    const int end = std::min(nn, (c + 1) * kNodeChunk);
    for (int i = c * kNodeChunk; i < end; ++i) {
      k += state_.mass[i] * (state_.vx[i] * state_.vx[i] + state_.vy[i] * state_.vy[i]);
      power += state_.fx[i] * state_.vx[i] + state_.fy[i] * state_.vy[i];
    }
    e.kinetic += 0.5 * k - 0.5 * last_dt_avg_ * power;
  }
  for (size_t b = 0; b < rigid_bodies_.size(); ++b)
    e.kinetic +=
        0.5 * rigid_bodies_[b].extra_mass *
        (rigid_states_[b].vx * rigid_states_[b].vx + rigid_states_[b].vy * rigid_states_[b].vy);
  e.initial_kinetic = initialized_ ? initial_kinetic_ : e.kinetic;
  e.initial_stored = initial_stored_;
  if (!options_.energy_terms) {  // only the kinetic energy is kept
    const double nan = std::numeric_limits<double>::quiet_NaN();
    e.initial_stored = e.internal = e.hourglass = e.damping = e.contact = e.friction = nan;
    e.external_loads = e.external = nan;
    return e;
  }
  e.internal = elements_.InternalEnergy();
  e.hourglass = elements_.HourglassEnergy();
  e.damping = damping_work_ + elements_.DampingEnergy();
  e.external_loads = load_work_;
  for (const ForceContributor* c : contributors_) {
    e.contact += c->StoredEnergy();
    e.friction += c->DissipatedEnergy();
    e.external_loads += c->ExternalWork();
  }
  e.external = e.external_loads + reaction_work_;
  return e;
}

SolverSummary ExplicitSolver::Run(double end_time) {
  if (!initialized_) Initialize();
  SolverSummary sum;
  sum.min_time_step = std::numeric_limits<double>::infinity();
  const long first = step_;
  const auto t0 = std::chrono::steady_clock::now();
  while (time_ < end_time) {
    Step();
    sum.min_time_step = std::min(sum.min_time_step, dt_);
    sum.max_time_step = std::max(sum.max_time_step, dt_);
  }
  const auto t1 = std::chrono::steady_clock::now();
  sum.steps = step_ - first;
  sum.time = time_;
  sum.wall_seconds = std::chrono::duration<double>(t1 - t0).count();
  sum.threads = threads_;
  if (sum.steps > 0 && elements_.num_elements() > 0)
    sum.ns_per_element_cycle =
        1e9 * sum.wall_seconds / (static_cast<double>(sum.steps) * elements_.num_elements());
  if (sum.steps == 0) sum.min_time_step = 0.0;
  sum.energies = energies();
  return sum;
}

}  // namespace spallkit::sim::solver
