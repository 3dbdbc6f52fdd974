#include "sim/contact/contact_pair.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/checkpoint_io.h"
#include "core/error.h"

namespace spallkit::sim::contact {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

double ContactResultant::NormalMagnitude() const { return std::hypot(normal_x, normal_y); }

ContactPair::ContactPair(std::string name,
                         ContactSurface slave,
                         ContactSurface master,
                         const ContactPairOptions& options)
    : name_(std::move(name)), options_(options), law_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw InputError("contact pair '" + name_ + "': " + error);
  auto check_surface = [&](const ContactSurface& s) {
    if (options_.penalty_law == PenaltyLaw::kBulkModulus &&
        static_cast<int>(s.bulk_stiffness.size()) != s.num_segments()) {
      throw InputError("contact pair '" + name_ + "': master surface '" + s.name +
                       "' has no element data for the bulk_modulus penalty law (build it with "
                       "MakeSurface or use mass_time_step / constant)");
    }
  };
  check_surface(master);
  if (options_.symmetric) check_surface(slave);
  passes_.resize(options_.symmetric ? 2 : 1);
  passes_[0].slave = slave;
  passes_[0].master = master;
  if (options_.symmetric) {
    passes_[1].slave = std::move(master);
    passes_[1].master = std::move(slave);
  }
  for (const Pass& p : passes_)
    for (const ContactSurface* surface : {&p.slave, &p.master})
      if (surface->curved() &&
          static_cast<int>(surface->segment_curvature.size()) != surface->num_segments())
        throw InputError("contact pair '" + name_ + "': surface '" + surface->name +
                         "' has a curvature for " +
                         std::to_string(surface->segment_curvature.size()) + " of its " +
                         std::to_string(surface->num_segments()) + " segments");
  for (Pass& p : passes_) {
    const int n = p.slave.num_nodes();
    if (options_.smooth_surfaces) {
      if (!p.slave.curved() || !p.master.curved())
        throw InputError("contact pair '" + name_ +
                         "': smooth_surfaces needs both surfaces curved (MarkCircularArcs)");
      p.spline.emplace(p);
    } else if (p.slave.curved()) {
      p.arcs.emplace(p);
    }
    if (p.spline || p.arcs) p.node_owned.assign(n, 0);
    p.tangential_force.assign(n, 0.0);
    p.tangential_stiffness.assign(n, 0.0);
    p.gap.assign(n, kInf);
    p.slots.assign(n, ContactSlot{});
    p.x_built.assign(p.master.num_nodes(), 0.0);
    p.y_built.assign(p.master.num_nodes(), 0.0);
    // Largest bulk-modulus penalty of the master (constant; StableTimeStep every step).
    double k_max = 0.0;
    for (double k : p.master.bulk_stiffness) k_max = std::max(k_max, options_.penalty_scale * k);
    max_penalty_.push_back(k_max);
  }
}

void ContactPair::AddForces(fe::NodalState& state, double t, double dt) {
  ComputeForces(state, t, dt);
  ApplyForces(state);
}

void ContactPair::ComputeForces(const fe::NodalState& state, double /*t*/, double dt) {
  forces_.Clear();
  if (!initialised_) {
    law_.set_reference_time_step(options_.reference_time_step > 0.0 ? options_.reference_time_step
                                                                    : dt);
    for (Pass& p : passes_) {
      const double mean = p.master.MeanSegmentLength(state.x.data(), state.y.data());
      p.margin = options_.search_margin > 0.0 ? options_.search_margin : mean;
      p.capture = options_.capture_depth > 0.0 ? options_.capture_depth : 0.5 * p.margin;
      p.capture = std::min(p.capture, 0.5 * p.margin);
    }
    initialised_ = true;
  }
  if (options_.smooth_surfaces && !spline_offsets_known_) {
    for (Pass& p : passes_) p.spline->MeasureOffsets(p, state.x.data(), state.y.data());
    spline_offsets_known_ = true;
  }
  resultant_ = ContactResultant{};
  stored_energy_ = 0.0;
  for (size_t i = 0; i < passes_.size(); ++i) RunPass(passes_[i], state, dt, i == 0 ? 1.0 : -1.0);
}

void ContactPair::RunPass(Pass& pass, const fe::NodalState& state, double dt, double sign) {
  const double* x = state.x.data();
  const double* y = state.y.data();
  if (!ReadyPass(pass, x, y)) return;
  if (pass.spline)
    pass.spline->Find(pass, x, y);
  else if (pass.arcs)
    pass.arcs->Find(pass, x, y);
  NodeContacts(pass, state, dt);
  if (pass.spline)
    pass.spline->Forces(pass, law_, state, dt);
  else if (pass.arcs)
    pass.arcs->Forces(pass, law_, state, dt);
  Scatter(pass, x, y, sign);
}

bool ContactPair::ReadyPass(Pass& pass, const double* x, const double* y) {
  const ContactSurface& slave = pass.slave;
  const ContactSurface& master = pass.master;
  const int ns = slave.num_nodes();

  // Bounding boxes and master motion since the last grid build (one pass over each surface).
  double mx0 = kInf, my0 = kInf, mx1 = -kInf, my1 = -kInf, moved2 = 0.0;
  for (int j = 0; j < master.num_nodes(); ++j) {
    const int g = master.nodes[j];
    mx0 = std::min(mx0, x[g]);
    mx1 = std::max(mx1, x[g]);
    my0 = std::min(my0, y[g]);
    my1 = std::max(my1, y[g]);
    const double dx = x[g] - pass.x_built[j], dy = y[g] - pass.y_built[j];
    moved2 = std::max(moved2, dx * dx + dy * dy);
  }
  double sx0 = kInf, sy0 = kInf, sx1 = -kInf, sy1 = -kInf;
  for (int i = 0; i < ns; ++i) {
    const int g = slave.nodes[i];
    sx0 = std::min(sx0, x[g]);
    sx1 = std::max(sx1, x[g]);
    sy0 = std::min(sy0, y[g]);
    sy1 = std::max(sy1, y[g]);
  }
  const double reach = 0.5 * pass.margin;
  const bool apart =
      sx0 > mx1 + reach || sx1 < mx0 - reach || sy0 > my1 + reach || sy1 < my0 - reach;
  if (apart) {
    // Far apart: no search. Release any tangential springs still loaded (the test keeps a
    // serial floating-point add out of this loop).
    for (int i = 0; i < ns; ++i) {
      if (pass.tangential_force[i] != 0.0)
        friction_dissipation_ +=
            ReleaseSpring(&pass.tangential_force[i], pass.tangential_stiffness[i]);
      pass.gap[i] = kInf;
    }
    friction_dissipation_ += ReleaseSpring(&pass.point_spring, pass.point_spring_stiffness);
    if (pass.arcs) pass.arcs->Clear();
    if (pass.spline) pass.spline->Clear();
    return false;
  }
  if (!pass.grid.built() || moved2 > reach * reach) {
    pass.grid.Build(master, x, y, pass.margin);
    for (int j = 0; j < master.num_nodes(); ++j) {
      pass.x_built[j] = x[master.nodes[j]];
      pass.y_built[j] = y[master.nodes[j]];
    }
    ++num_rebuilds_;
  }
  return true;
}

void ContactPair::NodeContacts(Pass& pass, const fe::NodalState& state, double dt) {
  const ContactSurface& slave = pass.slave;
  const ContactSurface& master = pass.master;
  const int ns = slave.num_nodes();
  const double* x = state.x.data();
  const double* y = state.y.data();
  const double* vx = state.vx.data();
  const double* vy = state.vy.data();
  const double* mass = state.mass.data();
  const double reach = 0.5 * pass.margin, capture = pass.capture;

  auto slave_node = [&](int i) {
    ContactSlot& slot = pass.slots[i];
    slot = ContactSlot{};
    if (!pass.node_owned.empty() && pass.node_owned[i]) {
      pass.gap[i] = kInf;  // the point contact touches for it and hands its spring on
      return;
    }
    const int s = slave.nodes[i];
    const Projection proj =
        ProjectOntoSurface(master, x, y, x[s], y[s], pass.grid.Candidates(x[s], y[s]));
    const bool near = proj.segment >= 0 && proj.distance <= reach;
    pass.gap[i] = near ? proj.gap : kInf;
    if (!near || proj.gap >= 0.0 || -proj.gap > capture) {
      // (With a point contact its Forces releases it, unless the point takes it over.)
      if (pass.node_owned.empty())
        slot.friction_work = ReleaseSpring(&pass.tangential_force[i], pass.tangential_stiffness[i]);
      return;
    }
    const int a = master.nodes[master.segment_a[proj.segment]];
    const int b = master.nodes[master.segment_b[proj.segment]];
    const double wa = 1.0 - proj.xi, wb = proj.xi;
    const double inv_mm = wa * wa * InverseMass(mass[a]) + wb * wb * InverseMass(mass[b]);
    const double k =
        law_.SegmentStiffness(master, proj.segment, mass[s], std::min(mass[a], mass[b]));
    ContactKinematics point;
    point.penetration = -proj.gap;
    point.nx = proj.nx, point.ny = proj.ny;
    point.rvx = vx[s] - wa * vx[a] - wb * vx[b];
    point.rvy = vy[s] - wa * vy[a] - wb * vy[b];
    point.inverse_mass_sum = InverseMass(mass[s]) + inv_mm;
    law_.Apply(k, point, dt, pass.NodeSpring(i), &slot);
    slot.segment = proj.segment;
    slot.xi = proj.xi;
  };
  // Below parallel_min_nodes no OpenMP region at all (an `if(false)` region still costs a team
  // allocation per call in libgomp when it has no thread pool).
  if (ns >= options_.parallel_min_nodes) {
#pragma omp parallel for schedule(static)
    for (int i = 0; i < ns; ++i) slave_node(i);
  } else {
    for (int i = 0; i < ns; ++i) slave_node(i);
  }
}

void ContactPair::Scatter(const Pass& pass, const double* x, const double* y, double sign) {
  const ContactSurface& slave = pass.slave;
  const ContactSurface& master = pass.master;
  // Node contacts in fixed slave order: deterministic for any thread count.
  for (int i = 0; i < slave.num_nodes(); ++i) {
    const ContactSlot& slot = pass.slots[i];
    friction_dissipation_ += slot.friction_work;
    if (slot.segment < 0) continue;
    damping_dissipation_ += slot.damping_work;
    stored_energy_ += slot.stored;
    const int s = slave.nodes[i];
    const int a = master.nodes[master.segment_a[slot.segment]];
    const int b = master.nodes[master.segment_b[slot.segment]];
    const double gx = slot.fnx + slot.ftx, gy = slot.fny + slot.fty;
    const double wa = 1.0 - slot.xi, wb = slot.xi;
    forces_.Add(s, gx, gy);
    forces_.Add(a, -(wa * gx), -(wa * gy));
    forces_.Add(b, -(wb * gx), -(wb * gy));
    AddToResultant(slot, sign);
  }
  if (!pass.spline && !pass.arcs) return;
  const ContactSlot& slot = pass.point_slot;
  friction_dissipation_ += slot.friction_work;
  if (slot.segment < 0) return;
  damping_dissipation_ += slot.damping_work;
  stored_energy_ += slot.stored;
  if (pass.spline)
    pass.spline->Scatter(pass, &forces_);
  else
    pass.arcs->Scatter(pass, x, y, &forces_);
  AddToResultant(slot, sign);
}

void ContactPair::AddToResultant(const ContactSlot& slot, double sign) {
  resultant_.normal_x += sign * slot.fnx;
  resultant_.normal_y += sign * slot.fny;
  resultant_.tangential_x += sign * slot.ftx;
  resultant_.tangential_y += sign * slot.fty;
  resultant_.normal_magnitude_sum += slot.fn;
  resultant_.active_nodes += 1;
  resultant_.max_penetration = std::max(resultant_.max_penetration, slot.penetration);
}

double ContactPair::StableTimeStep(const fe::NodalState& state) const {
  const double zeta = options_.normal_damping_ratio;
  const double damping_factor = std::sqrt(1.0 + zeta * zeta) - zeta;
  double omega2 = 0.0;
  if (options_.penalty_law == PenaltyLaw::kMassTimeStep) {
    const double dt_ref = initialised_ ? law_.reference_time_step() : options_.reference_time_step;
    if (!(dt_ref > 0.0)) return kInf;  // adapts to the first step it is given
    omega2 = 2.0 * options_.penalty_scale / (dt_ref * dt_ref);
  } else if (min_inverse_mass_state_ == &state) {
    omega2 = cached_omega2_;
  } else {
    for (size_t ip = 0; ip < passes_.size(); ++ip) {
      const Pass& p = passes_[ip];
      auto min_mass = [&](const ContactSurface& s) {
        double m = kInf;
        for (int g : s.nodes)
          if (state.mass[g] > 0.0) m = std::min(m, state.mass[g]);
        return m;
      };
      const double k_max = options_.penalty_law == PenaltyLaw::kBulkModulus
                               ? max_penalty_[ip]
                               : options_.constant_stiffness;
      const double inv = InverseMass(min_mass(p.slave)) + InverseMass(min_mass(p.master));
      omega2 = std::max(omega2, k_max * inv);
    }
    // Lumped masses and the penalty are fixed for a run: scan the surfaces once per state.
    if (omega2 > 0.0) min_inverse_mass_state_ = &state, cached_omega2_ = omega2;
  }
  // A node that is slave in one pass and master in the other carries both springs.
  if (passes_.size() > 1) omega2 *= 2.0;
  if (!(omega2 > 0.0)) return kInf;
  return options_.stable_step_safety * 2.0 / std::sqrt(omega2) * damping_factor;
}

std::string ContactPair::SaveState() const {
  CheckpointWriter out;
  out.Put(static_cast<int>(passes_.size()));
  out.Put(initialised_);
  for (double v :
       {law_.reference_time_step(), stored_energy_, friction_dissipation_, damping_dissipation_})
    out.Put(v);
  out.Put(num_rebuilds_);
  for (const Pass& p : passes_) {
    out.Put(p.slave.num_nodes());
    out.Put(p.margin);
    out.Put(p.capture);
    for (int i = 0; i < p.slave.num_nodes(); ++i) {
      out.Put(p.tangential_force[i]);
      out.Put(p.tangential_stiffness[i]);
      out.Put(p.gap[i]);
    }
    if (p.slave.curved()) {
      out.Put(p.point_spring);
      out.Put(p.point_spring_stiffness);
    }
    if (p.spline) p.spline->Save(&out);  // measured offsets and the Newton start
  }
  return out.Take();
}

void ContactPair::LoadState(const std::string& bytes) {
  CheckpointReader in(bytes, "contact pair '" + name_ + "': checkpoint state");
  if (in.Get<int>() != static_cast<int>(passes_.size()))
    throw InputError("contact pair '" + name_ + "': checkpoint has a different number of passes");
  initialised_ = in.Get<bool>();
  law_.set_reference_time_step(in.Get<double>());
  for (double* v : {&stored_energy_, &friction_dissipation_, &damping_dissipation_})
    *v = in.Get<double>();
  num_rebuilds_ = in.Get<int>();
  for (Pass& p : passes_) {
    if (in.Get<int>() != p.slave.num_nodes())
      throw InputError("contact pair '" + name_ + "': checkpoint surface size differs");
    p.margin = in.Get<double>();
    p.capture = in.Get<double>();
    for (int i = 0; i < p.slave.num_nodes(); ++i) {
      p.tangential_force[i] = in.Get<double>();
      p.tangential_stiffness[i] = in.Get<double>();
      p.gap[i] = in.Get<double>();
    }
    if (p.slave.curved()) {
      p.point_spring = in.Get<double>();
      p.point_spring_stiffness = in.Get<double>();
    }
    if (p.spline) {
      p.spline->Load(&in);
      spline_offsets_known_ = true;
    }
    p.grid = SegmentGrid{};  // rebuilt at the next step
  }
}

ContactPair MakeContactPair(const fe::Mesh& mesh,
                            const std::string& slave_curve,
                            const std::string& master_curve,
                            const std::vector<double>& bulk_modulus,
                            double thickness,
                            const ContactPairOptions& options) {
  return ContactPair(slave_curve + "/" + master_curve,
                     MakeSurface(mesh, slave_curve, bulk_modulus, thickness),
                     MakeSurface(mesh, master_curve, bulk_modulus, thickness),
                     options);
}

}  // namespace spallkit::sim::contact
