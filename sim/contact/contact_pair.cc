#include "sim/contact/contact_pair.h"

#include <ceres/jet.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "sim/contact/arc_geometry.h"

namespace spallkit::sim::contact {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// A closest point this close to a span's end (chord parameter) still counts as in span: where the
// contact direction passes exactly through a node (a rim node on the load line at t = 0), rounding
// would otherwise put it outside both arcs and drop the contact to the nodes, whose stiffness per
// node differs from the arc's (bench/contact_benchmark's 512-node rim: 2.4x the force).
constexpr double kSpanTolerance = 1e-9;
// Below this total blend weight (points within ~1e-6 of a span end, the weight ~ xi^2) the
// weights' gradient would divide rounding noise by ~0; the deepest point then acts alone.
constexpr double kMinBlendWeight = 1e-24;

double InverseMass(double m) { return m > 0.0 ? 1.0 / m : 0.0; }

// A tangential spring leaving contact: its stored energy 1/2 F^2 / k_t is dissipated (returned)
// and the spring is emptied.
double ReleaseSpring(double* force, double stiffness) {
  if (*force == 0.0) return 0.0;
  const double energy = 0.5 * *force * *force / stiffness;
  *force = 0.0;
  return energy;
}

// A force (fx, fy) acting at the arc point (px, py) of the chord na -> nb whose parameter is xi,
// as forces on the two nodes: chord weights (1 - xi, xi) plus a couple along the chord's normal
// that moves the line of action from the chord point back to the arc point (else a spinning
// roller meets a spurious torque ~ F L^3 / (16 rho^2)). Used for the tangential (friction) force,
// which must turn the roller about its centre.
void SpreadAtArcPoint(const double* x,
                      const double* y,
                      int na,
                      int nb,
                      double xi,
                      double px,
                      double py,
                      double fx_,
                      double fy_,
                      solver::ForceLog* forces) {
  const double ex = x[nb] - x[na], ey = y[nb] - y[na], l2 = ex * ex + ey * ey;
  const double cx = x[na] + xi * ex - px, cy = y[na] + xi * ey - py;  // chord point - arc point
  // +-tau (ey, -ex) at na / nb is a couple tau L^2; it cancels the moment error about the arc
  // point, (chord point - arc point) x force.
  const double tau = l2 > 0.0 ? -(cx * fy_ - cy * fx_) / l2 : 0.0;
  forces->Add(na, (1.0 - xi) * fx_ + tau * ey, (1.0 - xi) * fy_ - tau * ex);
  forces->Add(nb, xi * fx_ - tau * ey, xi * fy_ + tau * ex);
}

// The velocity that SpreadAtArcPoint's forces do work with (F . v = sum of node forces . node
// velocities): the chord point's plus the chord's turning rate times the offset to the arc point.
void ArcPointVelocity(const double* x,
                      const double* y,
                      const double* vx,
                      const double* vy,
                      int na,
                      int nb,
                      double xi,
                      double px,
                      double py,
                      double* wx,
                      double* wy) {
  const double ex = x[nb] - x[na], ey = y[nb] - y[na], l2 = ex * ex + ey * ey;
  const double cx = x[na] + xi * ex - px, cy = y[na] + xi * ey - py;
  const double turn = l2 > 0.0 ? (ey * (vx[na] - vx[nb]) - ex * (vy[na] - vy[nb])) / l2 : 0.0;
  *wx = (1.0 - xi) * vx[na] + xi * vx[nb] + turn * cy;
  *wy = (1.0 - xi) * vy[na] + xi * vy[nb] - turn * cx;
}

}  // namespace

bool ContactPairOptions::IsValid(std::string* error) const {
  std::ostringstream os;
  if (!(penalty_scale > 0.0) || !std::isfinite(penalty_scale)) {
    os << "penalty_scale must be finite and > 0, got " << penalty_scale;
  } else if (penalty_law == PenaltyLaw::kConstant && !(constant_stiffness > 0.0)) {
    os << "constant_stiffness must be > 0 N/m for the constant penalty law, got "
       << constant_stiffness;
  } else if (!(reference_time_step >= 0.0)) {
    os << "reference_time_step must be >= 0 s, got " << reference_time_step;
  } else if (!friction.IsValid(error)) {
    return false;
  } else if (!(tangential_stiffness_ratio > 0.0)) {
    os << "tangential_stiffness_ratio must be > 0, got " << tangential_stiffness_ratio;
  } else if (!(normal_damping_ratio >= 0.0)) {
    os << "normal_damping_ratio must be >= 0, got " << normal_damping_ratio;
  } else if (!(search_margin >= 0.0) || !(capture_depth >= 0.0)) {
    os << "search_margin and capture_depth must be >= 0 m";
  } else if (search_margin > 0.0 && capture_depth > 0.5 * search_margin) {
    os << "capture_depth (" << capture_depth << " m) must be <= search_margin / 2 ("
       << 0.5 * search_margin << " m)";
  } else if (!(stable_step_safety > 0.0 && stable_step_safety <= 1.0)) {
    os << "stable_step_safety must be in (0, 1], got " << stable_step_safety;
  } else {
    return true;
  }
  if (error) *error = os.str();
  return false;
}

double ContactResultant::NormalMagnitude() const { return std::hypot(normal_x, normal_y); }

ContactPair::ContactPair(std::string name,
                         ContactSurface slave,
                         ContactSurface master,
                         const ContactPairOptions& options)
    : name_(std::move(name)), options_(options) {
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
    if (p.slave.curved()) {
      const int m = p.slave.num_segments();
      p.arc_candidates.reserve(4 * m);  // no allocation in the time loop
      p.arc_blend.reserve(4 * m);
      p.node_owned.assign(n, 0);
      p.rim_node.assign(n, 0);
      for (int i = 0; i < n; ++i) {
        const int before = p.slave.segment_before[i], after = p.slave.segment_after[i];
        p.rim_node[i] = before >= 0 && after >= 0 && p.slave.segment_curvature[before] > 0.0 &&
                        p.slave.segment_curvature[after] > 0.0;
      }
      if (p.master.curved()) {
        p.master_arcs.assign(p.master.num_segments(), Arc<double>{});
        p.master_arc_stamp.assign(p.master.num_segments(), -1);
      }
    }
    if (options_.smooth_surfaces) {
      if (!p.slave.curved() || !p.master.curved())
        throw InputError("contact pair '" + name_ +
                         "': smooth_surfaces needs both surfaces curved (MarkCircularArcs)");
      // Topology now; the offsets need positions and are measured at the first step.
      p.slave_spline = MakeSplineSurface(p.slave);
      p.master_spline = MakeSplineSurface(p.master);
      p.spline_interior.assign(n, 0);
      for (int i = 0; i < n; ++i) {
        const SplineSurface& sp = p.slave_spline;
        const int a = sp.previous[i], b = sp.next[i];
        p.spline_interior[i] = a >= 0 && b >= 0 && sp.previous[a] >= 0 && sp.valid_span[i] &&
                               sp.valid_span[a] && sp.valid_span[sp.previous[a]] &&
                               sp.valid_span[b];
      }
    }
    p.tangential_force.assign(n, 0.0);
    p.tangential_stiffness.assign(n, 0.0);
    p.gap.assign(n, kInf);
    p.slots.assign(n, Slot{});
    p.x_built.assign(p.master.num_nodes(), 0.0);
    p.y_built.assign(p.master.num_nodes(), 0.0);
    // Largest bulk-modulus penalty of the master (constant; StableTimeStep every step).
    double k_max = 0.0;
    for (double k : p.master.bulk_stiffness) k_max = std::max(k_max, options_.penalty_scale * k);
    max_penalty_.push_back(k_max);
  }
}

double ContactPair::SegmentStiffness(const Pass& pass,
                                     int segment,
                                     double slave_mass,
                                     double master_mass) const {
  switch (options_.penalty_law) {
    case PenaltyLaw::kBulkModulus:
      return options_.penalty_scale * pass.master.bulk_stiffness[segment];
    case PenaltyLaw::kMassTimeStep: {
      double m =
          std::min(slave_mass > 0.0 ? slave_mass : kInf, master_mass > 0.0 ? master_mass : kInf);
      if (!std::isfinite(m)) m = 0.0;
      return MassTimeStepPenalty(options_.penalty_scale, m, reference_dt_);
    }
    case PenaltyLaw::kConstant:
      return options_.constant_stiffness;
  }
  return 0.0;
}

void ContactPair::AddForces(fe::NodalState& state, double t, double dt) {
  ComputeForces(state, t, dt);
  ApplyForces(state);
}

void ContactPair::ComputeForces(const fe::NodalState& state, double /*t*/, double dt) {
  forces_.Clear();
  if (!initialised_) {
    reference_dt_ = options_.reference_time_step > 0.0 ? options_.reference_time_step : dt;
    for (Pass& p : passes_) {
      const double mean = p.master.MeanSegmentLength(state.x.data(), state.y.data());
      p.margin = options_.search_margin > 0.0 ? options_.search_margin : mean;
      p.capture = options_.capture_depth > 0.0 ? options_.capture_depth : 0.5 * p.margin;
      p.capture = std::min(p.capture, 0.5 * p.margin);
    }
    initialised_ = true;
  }
  if (options_.smooth_surfaces && !spline_offsets_known_) {
    for (Pass& p : passes_) {
      p.slave_spline.offset =
          MeasureSplineOffset(p.slave, p.slave_spline, state.x.data(), state.y.data());
      p.master_spline.offset =
          MeasureSplineOffset(p.master, p.master_spline, state.x.data(), state.y.data());
    }
    spline_offsets_known_ = true;
  }
  resultant_ = ContactResultant{};
  stored_energy_ = 0.0;
  for (size_t i = 0; i < passes_.size(); ++i) RunPass(passes_[i], state, dt, i == 0 ? 1.0 : -1.0);
}

void ContactPair::RunPass(Pass& pass, const fe::NodalState& state, double dt, double sign) {
  const double* x = state.x.data();
  const double* y = state.y.data();
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
    // Far apart: no search. Release any tangential springs still loaded.
    // (Adding the released energy unconditionally put a serial floating-point add in this loop:
    // +40 % per node when far apart, bench/contact_benchmark.)
    for (int i = 0; i < ns; ++i) {
      if (pass.tangential_force[i] != 0.0)
        friction_dissipation_ +=
            ReleaseSpring(&pass.tangential_force[i], pass.tangential_stiffness[i]);
      pass.gap[i] = kInf;
    }
    friction_dissipation_ += ReleaseSpring(&pass.arc_spring, pass.arc_spring_stiffness);
    pass.arc_blend.clear();
    pass.spline_found = pass.spline_active = false;
    return;
  }
  if (!pass.grid.built() || moved2 > reach * reach) {
    pass.grid.Build(master, x, y, pass.margin);
    for (int j = 0; j < master.num_nodes(); ++j) {
      pass.x_built[j] = x[master.nodes[j]];
      pass.y_built[j] = y[master.nodes[j]];
    }
    ++num_rebuilds_;
  }
  if (options_.smooth_surfaces) {
    FindSplineContact(pass, x, y);
  } else if (slave.curved()) {
    FindArcContacts(pass, x, y);
    if (!pass.arc_blend.empty()) BlendArcContacts(pass, x, y);
  }

  const double* vx = state.vx.data();
  const double* vy = state.vy.data();
  const double* mass = state.mass.data();
  const double capture = pass.capture;

  auto slave_node = [&](int i) {
    Slot& slot = pass.slots[i];
    slot = Slot{};
    if (!pass.node_owned.empty() && pass.node_owned[i]) {
      pass.gap[i] = kInf;  // an adjacent arc touches for it; ArcForces hands its spring on
      return;
    }
    const int s = slave.nodes[i];
    const Projection proj =
        ProjectOntoSurface(master, x, y, x[s], y[s], pass.grid.Candidates(x[s], y[s]));
    const bool near = proj.segment >= 0 && proj.distance <= reach;
    pass.gap[i] = near ? proj.gap : kInf;
    if (!near || proj.gap >= 0.0 || -proj.gap > capture) {
      // (On a curved slave surface ArcForces releases it, unless an arc takes it over.)
      if (pass.node_owned.empty())
        slot.friction_work = ReleaseSpring(&pass.tangential_force[i], pass.tangential_stiffness[i]);
      return;
    }
    const int a = master.nodes[master.segment_a[proj.segment]];
    const int b = master.nodes[master.segment_b[proj.segment]];
    const double wa = 1.0 - proj.xi, wb = proj.xi;
    const double inv_mm = wa * wa * InverseMass(mass[a]) + wb * wb * InverseMass(mass[b]);
    const double k = SegmentStiffness(pass, proj.segment, mass[s], std::min(mass[a], mass[b]));
    ContactLaw(k,
               -proj.gap,
               proj.nx,
               proj.ny,
               vx[s] - wa * vx[a] - wb * vx[b],
               vy[s] - wa * vy[a] - wb * vy[b],
               InverseMass(mass[s]) + inv_mm,
               dt,
               &pass.tangential_force[i],
               &pass.tangential_stiffness[i],
               &slot);
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
  if (options_.smooth_surfaces)
    SplineForces(pass, state, dt);
  else if (slave.curved())
    ArcForces(pass, state, dt);

  // Scatter in fixed slave order: deterministic for any thread count.
  for (int i = 0; i < ns; ++i) {
    const Slot& slot = pass.slots[i];
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
  if (options_.smooth_surfaces) {
    const Slot& slot = pass.arc_slot;
    friction_dissipation_ += slot.friction_work;
    if (slot.segment >= 0) {
      damping_dissipation_ += slot.damping_work;
      stored_energy_ += slot.stored;
      // f n on the slave's control points by their B-spline weights, -f n on the master's: the
      // exact -grad of the penalty (spline_surface.h); friction the same way at the curve points.
      const double gx = slot.fnx + slot.ftx, gy = slot.fny + slot.fty;
      for (int j = 0; j < 4; ++j) {
        const double ws = pass.spline_slave_weights[j], wm = pass.spline_master_weights[j];
        forces_.Add(pass.spline_slave_nodes[j], ws * gx, ws * gy);
        forces_.Add(pass.spline_master_nodes[j], -(wm * gx), -(wm * gy));
      }
      AddToResultant(slot, sign);
    }
  } else if (slave.curved()) {
    const Slot& slot = pass.arc_slot;
    friction_dissipation_ += slot.friction_work;
    if (slot.segment >= 0) {
      damping_dissipation_ += slot.damping_work;
      stored_energy_ += slot.stored;
      // Normal force -f_n grad p (conservative, BlendArcContacts); friction at the arc points
      // (it turns the roller), by the blend's weights.
      for (const ArcContact& c : pass.arc_blend) {
        const std::array<int, 4> nodes = ArcNodes(pass, c);
        for (int j = 0; j < 4; ++j)
          forces_.Add(nodes[j], -(slot.fn * c.grad[2 * j]), -(slot.fn * c.grad[2 * j + 1]));
        if (c.third_node >= 0)
          forces_.Add(c.third_node, -(slot.fn * c.grad[8]), -(slot.fn * c.grad[9]));
        const double ftx = c.weight * slot.ftx, fty = c.weight * slot.fty;
        SpreadAtArcPoint(x, y, nodes[0], nodes[1], c.at.xi, c.at.px, c.at.py, ftx, fty, &forces_);
        SpreadAtArcPoint(
            x, y, nodes[2], nodes[3], c.at.xi_master, c.at.qx, c.at.qy, -ftx, -fty, &forces_);
      }
      AddToResultant(slot, sign);
    }
  }
}

std::array<int, 4> ContactPair::ArcNodes(const Pass& pass, const ArcContact& c) {
  const ContactSurface& s = pass.slave;
  const ContactSurface& m = pass.master;
  return {s.nodes[s.segment_a[c.slave_segment]],
          s.nodes[s.segment_b[c.slave_segment]],
          m.nodes[m.segment_a[c.master_segment]],
          m.nodes[m.segment_b[c.master_segment]]};
}

void ContactPair::AddToResultant(const Slot& slot, double sign) {
  resultant_.normal_x += sign * slot.fnx;
  resultant_.normal_y += sign * slot.fny;
  resultant_.tangential_x += sign * slot.ftx;
  resultant_.tangential_y += sign * slot.fty;
  resultant_.normal_magnitude_sum += slot.fn;
  resultant_.active_nodes += 1;
  resultant_.max_penetration = std::max(resultant_.max_penetration, slot.penetration);
}

void ContactPair::ContactLaw(double k,
                             double penetration,
                             double nx,
                             double ny,
                             double rvx,
                             double rvy,
                             double inverse_mass_sum,
                             double dt,
                             double* spring,
                             double* spring_stiffness,
                             Slot* slot) const {
  const double tx = -ny, ty = nx;
  const double vn = rvx * nx + rvy * ny, vt = rvx * tx + rvy * ty;
  const double fn_elastic = k * penetration;
  double fn = fn_elastic;
  const double zeta = options_.normal_damping_ratio;
  if (zeta > 0.0) {
    const double reduced = inverse_mass_sum > 0.0 ? 1.0 / inverse_mass_sum : 0.0;
    const double c = 2.0 * zeta * std::sqrt(k * reduced);
    fn = std::max(0.0, fn_elastic - c * vn);
    slot->damping_work = -(fn - fn_elastic) * vn * dt;
  }
  slot->stored = 0.5 * k * penetration * penetration;
  double ft = 0.0;
  if (!options_.friction.IsFrictionless()) {
    const double kt = options_.tangential_stiffness_ratio * k;
    const double mu = options_.friction.Coefficient(vt);
    const FrictionUpdate update = ReturnMap(*spring, vt * dt, kt, mu * fn);
    ft = update.force;
    slot->friction_work = update.dissipation;
    slot->stored += 0.5 * ft * ft / kt;
    *spring = ft;
    *spring_stiffness = kt;
  }
  slot->fn = fn;
  slot->penetration = penetration;
  slot->fnx = fn * nx;
  slot->fny = fn * ny;
  slot->ftx = ft * tx;
  slot->fty = ft * ty;
}

void ContactPair::FindArcContacts(Pass& pass, const double* x, const double* y) {
  const ContactSurface& slave = pass.slave;
  const ContactSurface& master = pass.master;
  std::fill(pass.node_owned.begin(), pass.node_owned.end(), 0);
  pass.arc_candidates.clear();
  pass.arc_blend.clear();
  ++pass.arc_stamp;
  for (int k = 0; k < slave.num_segments(); ++k) {
    const double kappa = slave.segment_curvature[k];
    if (!(kappa > 0.0)) continue;  // straight or concave slave segments touch by their nodes
    const int la = slave.segment_a[k], lb = slave.segment_b[k];
    const int sa = slave.nodes[la], sb = slave.nodes[lb];
    // Search from the chord's middle point (within the sagitta, << the grid's margin, of the
    // arc's); most arcs of a rim have no candidate and cost no more than this lookup.
    const std::span<const int> candidates =
        pass.grid.Candidates(0.5 * (x[sa] + x[sb]), 0.5 * (y[sa] + y[sb]));
    if (candidates.empty()) continue;
    const Arc arc = ArcThrough(x[sa], y[sa], x[sb], y[sb], kappa);
    // Master segment m's nodes and its arc (cached once per step; null for a straight segment).
    auto master_segment = [&](int m, double mp[4]) -> const Arc<double>* {
      const int ma = master.nodes[master.segment_a[m]], mb = master.nodes[master.segment_b[m]];
      mp[0] = x[ma], mp[1] = y[ma], mp[2] = x[mb], mp[3] = y[mb];
      if (!master.curved() || master.segment_curvature[m] == 0.0) return nullptr;
      if (pass.master_arc_stamp[m] != pass.arc_stamp) {  // once per step
        pass.master_arcs[m] = ArcThrough(mp[0], mp[1], mp[2], mp[3], master.segment_curvature[m]);
        pass.master_arc_stamp[m] = pass.arc_stamp;
      }
      return &pass.master_arcs[m];
    };
    // An arc's closest points on master segment m (its arc, or its chord).
    auto project = [&](const Arc<double>& slave_arc, int m, ArcPair<double>* g) {
      double mp[4];
      const Arc<double>* marc = master_segment(m, mp);
      return ArcClosestPoints(slave_arc, mp, marc, g);
    };
    auto in_span = [](double xi) { return xi >= -kSpanTolerance && xi <= 1.0 + kSpanTolerance; };
    // A ridge's point also records the third node and curvature that bound its wedge and where
    // in the wedge it is (0 .. 1 between the two arcs' end normals).
    auto add = [&](const ArcPair<double>& g,
                   int slave_segment,
                   int m,
                   bool slave_node,
                   bool master_node,
                   int third_node = -1,
                   double third_curvature = 0.0,
                   double wedge = 0.0) {
      ArcContact c;
      c.at = g;
      c.slave_segment = slave_segment;
      c.master_segment = m;
      c.slave_node = slave_node;
      c.master_node = master_node;
      c.third_node = third_node;
      c.third_curvature = third_curvature;
      c.wedge = wedge;
      pass.arc_candidates.push_back(c);
    };
    // The rim node where this arc starts, when it joins the previous convex arc (a ridge there
    // is this arc's and the previous one's points falling past that node on either side).
    const int before = slave.segment_before[la];
    const bool ridge_possible = before >= 0 && slave.segment_curvature[before] > 0.0;
    for (int m : candidates) {
      ArcPair<double> g;
      if (!project(arc, m, &g)) continue;
      g.xi = ChordParameter(x[sa], y[sa], x[sb], y[sb], g.px, g.py);
      if (g.xi < -kSpanTolerance) {
        // Before this arc's start: the node sa is the closest slave point if the previous arc's
        // point falls past its end.
        // (Only next to the node: a kink turns the closest point by r x kink, well under a
        // segment; most rim arcs' points lie far outside their spans and skip this.)
        if (!ridge_possible || g.xi < -1.0) continue;
        const int pa = slave.nodes[slave.segment_a[before]];
        const Arc prev = ArcThrough(x[pa], y[pa], x[sa], y[sa], slave.segment_curvature[before]);
        ArcPair<double> h;
        if (!project(prev, m, &h)) continue;
        const double past = ChordParameter(x[pa], y[pa], x[sa], y[sa], h.px, h.py) - 1.0;
        if (!(past > kSpanTolerance)) continue;
        const double wedge = past / (past - g.xi);
        double mp[4];
        const Arc<double>* marc = master_segment(m, mp);
        if (!NodeArcClosestPoints(x[sa], y[sa], mp, marc, &h) || !in_span(h.xi_master)) continue;
        add(h, before, m, true, false, sb, kappa, wedge);
        continue;
      }
      if (g.xi_master > 1.0 + kSpanTolerance) {
        // Past m's end: a ridge if it also falls before the start of the next arc (both arcs of
        // one curved surface, bending the same way: a raceway's rim, not a pocket's corner).
        const int node = master.segment_b[m], next = master.segment_after[node];
        ArcPair<double> h;
        if (g.xi_master > 2.0 || next < 0 || !master.curved() ||
            master.segment_curvature[m] == 0.0 ||
            master.segment_curvature[m] * master.segment_curvature[next] <= 0.0 ||
            !project(arc, next, &h) || !(h.xi_master < -kSpanTolerance))
          continue;
        const double past = g.xi_master - 1.0, wedge = past / (past - h.xi_master);
        const int n = master.nodes[node];
        if (!ArcNodeClosestPoints(arc, x[n], y[n], &g)) continue;
        g.xi = ChordParameter(x[sa], y[sa], x[sb], y[sb], g.px, g.py);
        if (!in_span(g.xi)) continue;
        add(g,
            k,
            m,
            false,
            true,
            master.nodes[master.segment_b[next]],
            master.segment_curvature[next],
            wedge);
        continue;
      }
      if (!in_span(g.xi_master) || !in_span(g.xi)) continue;
      add(g, k, m, false, false);
    }
  }
  // One contact per pass: the deepest point and the points of the slave arcs chained to it (a
  // dented node gives two, see the header). With none (the closest direction falls on a kink
  // between two deformed arcs, or a spall faces the master) every node keeps node contact.
  const std::vector<ArcContact>& cand = pass.arc_candidates;
  if (cand.empty()) return;
  size_t deepest = 0;
  for (size_t i = 1; i < cand.size(); ++i)
    if (cand[i].at.gap < cand[deepest].at.gap) deepest = i;
  auto has_point = [&](int k) {
    for (const ArcContact& c : cand)
      if (c.slave_segment == k) return true;
    return false;
  };
  // Walk the chain both ways from the deepest point's arc (a closed rim: at most once round).
  const int k0 = cand[deepest].slave_segment, n = slave.num_segments();
  auto previous = [&](int k) { return slave.segment_before[slave.segment_a[k]]; };
  auto next = [&](int k) { return slave.segment_after[slave.segment_b[k]]; };
  int lo = k0, hi = k0, length = 1;
  while (length < n && previous(lo) >= 0 && has_point(previous(lo))) lo = previous(lo), ++length;
  while (length < n && next(hi) >= 0 && has_point(next(hi))) hi = next(hi), ++length;
  auto in_chain = [&](int k) {
    for (int j = lo, steps = 0; steps < length; ++steps) {
      if (j == k) return true;
      j = next(j);
    }
    return false;
  };
  for (const ArcContact& c : cand)
    if (in_chain(c.slave_segment)) pass.arc_blend.push_back(c);
  // BlendArcContacts shares weights within the points of one slave arc or ridge node, taken as a
  // run: a ridge point is filed under the arc before its node but found while searching the arc
  // after it, so order the blend by that key (insertion sort: a handful of points, no allocation).
  auto key = [](const ArcContact& c) { return 2 * c.slave_segment + (c.slave_node ? 1 : 0); };
  std::vector<ArcContact>& blend = pass.arc_blend;
  for (size_t i = 1; i < blend.size(); ++i)
    for (size_t j = i; j > 0 && key(blend[j - 1]) > key(blend[j]); --j)
      std::swap(blend[j - 1], blend[j]);
  // Nodes the arc contact stands for: the blend's arcs' ends, and every node between two convex
  // arcs (an interior point of the smooth rim; node contact there would count the overlap twice).
  for (const ArcContact& b : pass.arc_blend) {
    pass.node_owned[slave.segment_a[b.slave_segment]] = 1;
    pass.node_owned[slave.segment_b[b.slave_segment]] = 1;
  }
  for (int i = 0; i < slave.num_nodes(); ++i) pass.node_owned[i] |= pass.rim_node[i];
}

namespace {
// The blend's span factor: (xi (1 - xi))^2 vanishes, with its slope, at both ends of a span, so a
// point joins and leaves the blend smoothly. T = double or a Jet (its gradient).
template <typename T>
T SpanWeight(const T& xi) {
  const T w = xi * (1.0 - xi);
  return w * w;
}
// A ridge node's span is its wedge: the factor on its side is SpanWeight(wedge parameter), which
// vanishes where the wedge hands over to an arc's span end (also vanishing there).
template <typename T>
T SlaveFactor(const ArcPair<T>& g, bool slave_node, const T& wedge) {
  return SpanWeight(slave_node ? wedge : g.xi);
}
template <typename T>
T MasterFactor(const ArcPair<T>& g, bool master_node, const T& wedge) {
  return SpanWeight(master_node ? wedge : g.xi_master);
}
// Where a ridge point is in its wedge, 0 .. 1 (FindArcContacts' values, here on Jets for the
// gradient). Slave ridge at node s[2..3] between the arc s[0..3] (curvature ks) and the next arc
// s[2..3] -> t (kt): how far the first arc's closest point to master m falls past its end and the
// next one's before its start. Master ridge at m[2..3] between arc m and the next master arc
// m[2..3] -> t (kt), the same for the slave arc's closest points on them.
template <typename T>
T SlaveWedge(const T s[4], double ks, const T t[2], double kt, const T m[4], double km) {
  const T next[4] = {s[2], s[3], t[0], t[1]};
  ArcPair<T> a, b;
  ArcClosestPoints(s, ks, m, km, &a);
  ArcClosestPoints(next, kt, m, km, &b);
  const T past = a.xi - 1.0;
  return past / (past - b.xi);
}
template <typename T>
T MasterWedge(const T s[4], double ks, const T m[4], double km, const T t[2], double kt) {
  const T next[4] = {m[2], m[3], t[0], t[1]};
  ArcPair<T> a, b;
  ArcClosestPoints(s, ks, m, km, &a);
  ArcClosestPoints(s, ks, next, kt, &b);
  const T past = a.xi_master - 1.0;
  return past / (past - b.xi_master);
}
}  // namespace

void ContactPair::BlendArcContacts(Pass& pass, const double* x, const double* y) const {
  // p = sum w_c p_c / sum w_c over the blend's points, w_c = S_c omega_c: the slave span factor
  // S_c = SpanWeight(xi_c) times the point's share of its slave arc's master factors,
  // omega_c = M_c / sum_g M, M_c = SpanWeight(xi_master_c), over the points g of the same slave
  // arc or ridge node (its points on neighbouring master arcs). A ridge point's factor on its
  // node's side is SpanWeight of its place in the wedge.
  // Why the share: with plain products S_c M_c, a slave arc's point crossing a master node has
  // both its points at a master span end, its weight ~ 0 beside a second arc's point near its own
  // end, and the ratio of the two vanishing weights swung over nanometres of motion (200x the
  // penalty stiffness on the 0.25 mm mesh: session 8's energy defect, docs/CONTACT.md). The share
  // keeps the slave arc's weight whole across the node.
  // The gradient, weights included, by forward-mode automatic differentiation of each point's
  // geometry over its coordinates (ceres::Jet):
  //   dp = (1/W) sum_c [w_c dp_c + (p_c - p) omega_c dS_c + ((p_c - p) S_c - A_g) dM_c / sum_g M],
  //   A_g = sum_{c in g} omega_c (p_c - p) S_c,  W = sum w_c.
  // With that the normal force -f_n grad p is conservative for the blended penalty k p^2 / 2.
  using Jet = ceres::Jet<double, kArcCoordinates>;
  const ContactSurface& slave = pass.slave;
  const ContactSurface& master = pass.master;
  std::vector<ArcContact>& blend = pass.arc_blend;
  auto group_end = [&](size_t g0) {  // the run of points of one slave arc (or ridge node)
    size_t g1 = g0;
    while (g1 < blend.size() && blend[g1].slave_segment == blend[g0].slave_segment &&
           blend[g1].slave_node == blend[g0].slave_node)
      ++g1;
    return g1;
  };
  double total = 0.0, penetration = 0.0;
  for (size_t g0 = 0, g1; g0 < blend.size(); g0 = g1) {
    g1 = group_end(g0);
    double sum = 0.0;
    for (size_t i = g0; i < g1; ++i)
      sum += blend[i].master_sum = MasterFactor(blend[i].at, blend[i].master_node, blend[i].wedge);
    for (size_t i = g0; i < g1; ++i) {
      ArcContact& c = blend[i];
      c.omega = sum > 0.0 ? c.master_sum / sum : 1.0 / double(g1 - g0);
      c.master_sum = sum;
      c.weight = SlaveFactor(c.at, c.slave_node, c.wedge) * c.omega;
      total += c.weight;
      penetration -= c.weight * c.at.gap;
    }
  }
  if (!(total > kMinBlendWeight)) {  // all at span ends (a node): the deepest alone, weight fixed
    size_t deepest = 0;
    for (size_t i = 1; i < blend.size(); ++i)
      if (blend[i].at.gap < blend[deepest].at.gap) deepest = i;
    blend[0] = blend[deepest];
    blend.resize(1);
    blend[0].weight = blend[0].omega = total = 1.0;
    blend[0].master_sum = 0.0;
    penetration = -blend[0].at.gap;
  } else {
    penetration /= total;
  }
  const bool fixed_weight = blend.size() == 1;
  for (size_t g0 = 0, g1; g0 < blend.size(); g0 = g1) {
    g1 = group_end(g0);
    double a_g = 0.0;
    for (size_t i = g0; i < g1; ++i) {
      const ArcContact& c = blend[i];
      a_g += c.omega * (-c.at.gap - penetration) * SlaveFactor(c.at, c.slave_node, c.wedge);
    }
    for (size_t i = g0; i < g1; ++i) {
      ArcContact& c = blend[i];
      const std::array<int, 4> nodes = ArcNodes(pass, c);
      Jet s[4], m[4], t[2];  // t: a ridge's third node (the next arc's end), coordinates 8, 9
      for (int j = 0; j < 2; ++j) {
        s[2 * j] = Jet(x[nodes[j]], 2 * j);
        s[2 * j + 1] = Jet(y[nodes[j]], 2 * j + 1);
        m[2 * j] = Jet(x[nodes[2 + j]], 4 + 2 * j);
        m[2 * j + 1] = Jet(y[nodes[2 + j]], 5 + 2 * j);
      }
      if (c.third_node >= 0) t[0] = Jet(x[c.third_node], 8), t[1] = Jet(y[c.third_node], 9);
      const double ks = slave.segment_curvature[c.slave_segment];
      const double km = master.curved() ? master.segment_curvature[c.master_segment] : 0.0;
      ArcPair<Jet> g;
      Jet wedge(0.0);
      if (c.slave_node) {
        NodeArcClosestPoints(&s[2], m, km, &g);  // the node is the slave segment's end b
        wedge = SlaveWedge(s, ks, t, c.third_curvature, m, km);
      } else if (c.master_node) {
        ArcNodeClosestPoints(s, ks, &m[2], &g);  // the node is the master segment's end b
        wedge = MasterWedge(s, ks, m, km, t, c.third_curvature);
      } else {
        ArcClosestPoints(s, ks, m, km, &g);
      }
      c.weight /= total;
      const double dp = -c.at.gap - penetration;
      const Jet sf = SlaveFactor(g, c.slave_node, wedge),
                mf = MasterFactor(g, c.master_node, wedge);
      const double m_coef = c.master_sum > 0.0 ? (dp * sf.a - a_g) / c.master_sum : 0.0;
      for (int d = 0; d < kArcCoordinates; ++d) {
        c.grad[d] = -c.weight * g.gap.v[d];
        if (!fixed_weight) c.grad[d] += (dp * c.omega * sf.v[d] + m_coef * mf.v[d]) / total;
      }
    }
  }
}

void ContactPair::ArcForces(Pass& pass, const fe::NodalState& state, double dt) {
  const ContactSurface& slave = pass.slave;
  const double* x = state.x.data();
  const double* y = state.y.data();
  const double* vx = state.vx.data();
  const double* vy = state.vy.data();
  const double* mass = state.mass.data();
  Slot& slot = pass.arc_slot;
  slot = Slot{};
  double penetration = 0.0;
  for (const ArcContact& c : pass.arc_blend) penetration -= c.weight * c.at.gap;
  if (!pass.arc_blend.empty() && penetration > 0.0 && penetration <= pass.capture) {
    if (pass.arc_spring == 0.0) {
      // Hand-over: the contact walked here from a node.
      for (const ArcContact& c : pass.arc_blend)
        for (int local : {slave.segment_a[c.slave_segment], slave.segment_b[c.slave_segment]})
          if (pass.arc_spring == 0.0 && pass.slots[local].segment < 0 &&
              pass.tangential_force[local] != 0.0)
            std::swap(pass.arc_spring, pass.tangential_force[local]);
    }
    // Blended stiffness, mass and normal; relative velocities conjugate to how the forces are
    // spread: the normal one is -dp/dt, the tangential one the arc points' slip.
    double k = 0.0, inverse_mass = 0.0, nx = 0.0, ny = 0.0, vn = 0.0, sx = 0.0, sy = 0.0;
    for (const ArcContact& c : pass.arc_blend) {
      const std::array<int, 4> nodes = ArcNodes(pass, c);
      const double ws = c.at.xi, wm = c.at.xi_master;
      k += c.weight * SegmentStiffness(pass,
                                       c.master_segment,
                                       std::min(mass[nodes[0]], mass[nodes[1]]),
                                       std::min(mass[nodes[2]], mass[nodes[3]]));
      inverse_mass += c.weight * ((1.0 - ws) * (1.0 - ws) * InverseMass(mass[nodes[0]]) +
                                  ws * ws * InverseMass(mass[nodes[1]]) +
                                  (1.0 - wm) * (1.0 - wm) * InverseMass(mass[nodes[2]]) +
                                  wm * wm * InverseMass(mass[nodes[3]]));
      nx += c.weight * c.at.nx;
      ny += c.weight * c.at.ny;
      for (int j = 0; j < 4; ++j)
        vn -= c.grad[2 * j] * vx[nodes[j]] + c.grad[2 * j + 1] * vy[nodes[j]];
      if (c.third_node >= 0) vn -= c.grad[8] * vx[c.third_node] + c.grad[9] * vy[c.third_node];
      // Slip of the arc points (the work-conjugate of SpreadAtArcPoint), blended.
      double tsx, tsy, tmx, tmy;
      ArcPointVelocity(x, y, vx, vy, nodes[0], nodes[1], c.at.xi, c.at.px, c.at.py, &tsx, &tsy);
      ArcPointVelocity(
          x, y, vx, vy, nodes[2], nodes[3], c.at.xi_master, c.at.qx, c.at.qy, &tmx, &tmy);
      sx += c.weight * (tsx - tmx);
      sy += c.weight * (tsy - tmy);
    }
    const double nl = std::hypot(nx, ny);
    nx /= nl, ny /= nl;
    const double vt = -sx * ny + sy * nx;  // along t = (-ny, nx)
    ContactLaw(k,
               penetration,
               nx,
               ny,
               vn * nx - vt * ny,
               vn * ny + vt * nx,
               inverse_mass,
               dt,
               &pass.arc_spring,
               &pass.arc_spring_stiffness,
               &slot);
    slot.segment = pass.arc_blend.front().master_segment;
    slot.xi = pass.arc_blend.front().at.xi_master;
  } else {
    // Out of contact: the spring's energy is dissipated, as for a node.
    slot.friction_work += ReleaseSpring(&pass.arc_spring, pass.arc_spring_stiffness);
  }
  ReleaseIdleNodeSprings(pass);
}

void ContactPair::ReleaseIdleNodeSprings(Pass& pass) {
  for (int i = 0; i < pass.slave.num_nodes(); ++i)
    if (pass.slots[i].segment < 0)
      pass.slots[i].friction_work +=
          ReleaseSpring(&pass.tangential_force[i], pass.tangential_stiffness[i]);
}

void ContactPair::FindSplineContact(Pass& pass, const double* x, const double* y) {
  const ContactSurface& slave = pass.slave;
  const ContactSurface& master = pass.master;
  const SplineSurface& ss = pass.slave_spline;
  const SplineSurface& ms = pass.master_spline;
  pass.node_owned = pass.spline_interior;
  pass.spline_active = false;
  // Newton from last step's point; if that fails (first contact, a spall passing), from the
  // slave control node nearest the master.
  SplineContactPoint point = pass.spline_point;
  bool found = pass.spline_found && SplineClosestPoints(slave, ss, master, ms, x, y, &point);
  if (!found) {
    int best = -1, best_segment = -1;
    double best_gap = kInf, best_xi = 0.0;
    for (int i = 0; i < slave.num_nodes(); ++i) {
      if (!ss.valid_span[i] && !(ss.previous[i] >= 0 && ss.valid_span[ss.previous[i]])) continue;
      const int g = slave.nodes[i];
      const std::span<const int> candidates = pass.grid.Candidates(x[g], y[g]);
      if (candidates.empty()) continue;
      const Projection proj = ProjectOntoSurface(master, x, y, x[g], y[g], candidates);
      if (proj.segment < 0 || !(proj.gap < best_gap)) continue;
      best = i, best_gap = proj.gap, best_segment = proj.segment, best_xi = proj.xi;
    }
    if (best >= 0) {
      point = SplineContactPoint{};
      point.slave_span = ss.valid_span[best] ? best : ss.previous[best];
      point.t = ss.valid_span[best] ? 0.0 : 1.0;
      point.master_span = master.segment_a[best_segment];
      point.s = std::clamp(best_xi, 0.0, 1.0);
      found = SplineClosestPoints(slave, ss, master, ms, x, y, &point);
    }
  }
  pass.spline_found = found;
  if (!found) return;
  pass.spline_point = point;
  if (!(point.gap < 0.0) || -point.gap > pass.capture) return;
  pass.spline_active = true;
  const SplineBasis bs(point.t), bm(point.s);
  const std::array<int, 4> cs = ss.Controls(point.slave_span), cm = ms.Controls(point.master_span);
  for (int j = 0; j < 4; ++j) {
    pass.node_owned[cs[j]] = 1;  // the spline contact stands for them
    pass.spline_slave_nodes[j] = slave.nodes[cs[j]];
    pass.spline_master_nodes[j] = master.nodes[cm[j]];
    pass.spline_slave_weights[j] = bs.b[j];
    pass.spline_master_weights[j] = bm.b[j];
  }
}

void ContactPair::SplineForces(Pass& pass, const fe::NodalState& state, double dt) {
  const double* vx = state.vx.data();
  const double* vy = state.vy.data();
  const double* mass = state.mass.data();
  Slot& slot = pass.arc_slot;
  slot = Slot{};
  if (pass.spline_active) {
    const std::array<int, 4> cs = pass.slave_spline.Controls(pass.spline_point.slave_span);
    if (pass.arc_spring == 0.0) {
      // Hand-over: the contact walked here from a node.
      for (int local : cs)
        if (pass.arc_spring == 0.0 && pass.slots[local].segment < 0 &&
            pass.tangential_force[local] != 0.0)
          std::swap(pass.arc_spring, pass.tangential_force[local]);
    }
    // Stiffness of the master segment under the point; mass and velocities conjugate to the
    // weights the forces are spread with.
    double inverse_mass = 0.0, rvx = 0.0, rvy = 0.0;
    double slave_mass = kInf, master_mass = kInf;
    for (int j = 0; j < 4; ++j) {
      const int a = pass.spline_slave_nodes[j], b = pass.spline_master_nodes[j];
      const double ws = pass.spline_slave_weights[j], wm = pass.spline_master_weights[j];
      inverse_mass += ws * ws * InverseMass(mass[a]) + wm * wm * InverseMass(mass[b]);
      rvx += ws * vx[a] - wm * vx[b];
      rvy += ws * vy[a] - wm * vy[b];
      slave_mass = std::min(slave_mass, mass[a]);
      master_mass = std::min(master_mass, mass[b]);
    }
    const SplineContactPoint& p = pass.spline_point;
    const int segment = pass.master.segment_after[p.master_span];
    ContactLaw(SegmentStiffness(pass, segment, slave_mass, master_mass),
               -p.gap,
               p.nx,
               p.ny,
               rvx,
               rvy,
               inverse_mass,
               dt,
               &pass.arc_spring,
               &pass.arc_spring_stiffness,
               &slot);
    slot.segment = segment;
    slot.xi = p.s;
  } else {
    slot.friction_work += ReleaseSpring(&pass.arc_spring, pass.arc_spring_stiffness);
  }
  ReleaseIdleNodeSprings(pass);
}

double ContactPair::StableTimeStep(const fe::NodalState& state) const {
  const double zeta = options_.normal_damping_ratio;
  const double damping_factor = std::sqrt(1.0 + zeta * zeta) - zeta;
  double omega2 = 0.0;
  if (options_.penalty_law == PenaltyLaw::kMassTimeStep) {
    const double dt_ref = initialised_ ? reference_dt_ : options_.reference_time_step;
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
    // Lumped masses and the penalty are fixed for a run: scan the surfaces once per state
    // (the scan was ~2.4 % of a full-FE step at 0.25 mm).
    if (omega2 > 0.0) min_inverse_mass_state_ = &state, cached_omega2_ = omega2;
  }
  // A node that is slave in one pass and master in the other carries both springs.
  if (passes_.size() > 1) omega2 *= 2.0;
  if (!(omega2 > 0.0)) return kInf;
  return options_.stable_step_safety * 2.0 / std::sqrt(omega2) * damping_factor;
}

namespace {
template <typename T>
void Put(std::string* out, const T& v) {
  out->append(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <typename T>
T Get(const std::string& in, size_t* pos, const std::string& name) {
  if (*pos + sizeof(T) > in.size())
    throw InputError("contact pair '" + name + "': truncated checkpoint state");
  T v;
  std::memcpy(&v, in.data() + *pos, sizeof(T));
  *pos += sizeof(T);
  return v;
}
}  // namespace

std::string ContactPair::SaveState() const {
  std::string out;
  Put(&out, static_cast<int>(passes_.size()));
  Put(&out, initialised_);
  for (double v : {reference_dt_, stored_energy_, friction_dissipation_, damping_dissipation_})
    Put(&out, v);
  Put(&out, num_rebuilds_);
  for (const Pass& p : passes_) {
    Put(&out, p.slave.num_nodes());
    Put(&out, p.margin);
    Put(&out, p.capture);
    for (int i = 0; i < p.slave.num_nodes(); ++i) {
      Put(&out, p.tangential_force[i]);
      Put(&out, p.tangential_stiffness[i]);
      Put(&out, p.gap[i]);
    }
    if (p.slave.curved()) {
      Put(&out, p.arc_spring);
      Put(&out, p.arc_spring_stiffness);
    }
    if (options_.smooth_surfaces) {  // measured offsets and the Newton start
      Put(&out, p.slave_spline.offset);
      Put(&out, p.master_spline.offset);
      Put(&out, p.spline_found);
      Put(&out, p.spline_point);
    }
  }
  return out;
}

void ContactPair::LoadState(const std::string& bytes) {
  size_t pos = 0;
  if (Get<int>(bytes, &pos, name_) != static_cast<int>(passes_.size()))
    throw InputError("contact pair '" + name_ + "': checkpoint has a different number of passes");
  initialised_ = Get<bool>(bytes, &pos, name_);
  reference_dt_ = Get<double>(bytes, &pos, name_);
  stored_energy_ = Get<double>(bytes, &pos, name_);
  friction_dissipation_ = Get<double>(bytes, &pos, name_);
  damping_dissipation_ = Get<double>(bytes, &pos, name_);
  num_rebuilds_ = Get<int>(bytes, &pos, name_);
  for (Pass& p : passes_) {
    if (Get<int>(bytes, &pos, name_) != p.slave.num_nodes())
      throw InputError("contact pair '" + name_ + "': checkpoint surface size differs");
    p.margin = Get<double>(bytes, &pos, name_);
    p.capture = Get<double>(bytes, &pos, name_);
    for (int i = 0; i < p.slave.num_nodes(); ++i) {
      p.tangential_force[i] = Get<double>(bytes, &pos, name_);
      p.tangential_stiffness[i] = Get<double>(bytes, &pos, name_);
      p.gap[i] = Get<double>(bytes, &pos, name_);
    }
    if (p.slave.curved()) {
      p.arc_spring = Get<double>(bytes, &pos, name_);
      p.arc_spring_stiffness = Get<double>(bytes, &pos, name_);
    }
    if (options_.smooth_surfaces) {
      p.slave_spline.offset = Get<double>(bytes, &pos, name_);
      p.master_spline.offset = Get<double>(bytes, &pos, name_);
      p.spline_found = Get<bool>(bytes, &pos, name_);
      p.spline_point = Get<SplineContactPoint>(bytes, &pos, name_);
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
