#include "sim/contact/spline_contact.h"

#include <algorithm>
#include <limits>
#include <span>

#include "sim/contact/segment_grid.h"

namespace spallkit::sim::contact {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

SplineContact::SplineContact(const ContactPass& pass)
    : slave_spline_(MakeSplineSurface(pass.slave)), master_spline_(MakeSplineSurface(pass.master)) {
  // Topology now; the offsets need positions and are measured at the first step.
  const SplineSurface& sp = slave_spline_;
  const int n = pass.slave.num_nodes();
  interior_.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    const int a = sp.previous[i], b = sp.next[i];
    interior_[i] = a >= 0 && b >= 0 && sp.previous[a] >= 0 && sp.valid_span[i] &&
                   sp.valid_span[a] && sp.valid_span[sp.previous[a]] && sp.valid_span[b];
  }
}

void SplineContact::MeasureOffsets(const ContactPass& pass, const double* x, const double* y) {
  slave_spline_.offset = MeasureSplineOffset(pass.slave, slave_spline_, x, y);
  master_spline_.offset = MeasureSplineOffset(pass.master, master_spline_, x, y);
}

void SplineContact::Find(ContactPass& pass, const double* x, const double* y) {
  const ContactSurface& slave = pass.slave;
  const ContactSurface& master = pass.master;
  const SplineSurface& ss = slave_spline_;
  const SplineSurface& ms = master_spline_;
  pass.node_owned = interior_;
  active_ = false;
  // Newton from last step's point; if that fails (first contact, a spall passing), from the
  // slave control node nearest the master.
  SplineContactPoint point = point_;
  bool found = found_ && SplineClosestPoints({slave, ss}, {master, ms}, x, y, &point);
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
      found = SplineClosestPoints({slave, ss}, {master, ms}, x, y, &point);
    }
  }
  found_ = found;
  if (!found) return;
  point_ = point;
  if (!(point.gap < 0.0) || -point.gap > pass.capture) return;
  active_ = true;
  const SplineBasis bs(point.t), bm(point.s);
  const std::array<int, 4> cs = ss.Controls(point.slave_span), cm = ms.Controls(point.master_span);
  for (int j = 0; j < 4; ++j) {
    pass.node_owned[cs[j]] = 1;  // the spline contact stands for them
    slave_nodes_[j] = slave.nodes[cs[j]];
    master_nodes_[j] = master.nodes[cm[j]];
    slave_weights_[j] = bs.b[j];
    master_weights_[j] = bm.b[j];
  }
}

void SplineContact::Forces(ContactPass& pass,
                           const ContactLaw& law,
                           const fe::NodalState& state,
                           double dt) {
  const double* vx = state.vx.data();
  const double* vy = state.vy.data();
  const double* mass = state.mass.data();
  ContactSlot& slot = pass.point_slot;
  slot = ContactSlot{};
  if (active_) {
    const std::array<int, 4> cs = slave_spline_.Controls(point_.slave_span);
    for (int local : cs) pass.TakeNodeSpring(local);  // the contact walked here from a node
    // Stiffness of the master segment under the point; mass and velocities conjugate to the
    // weights the forces are spread with.
    double inverse_mass = 0.0, rvx = 0.0, rvy = 0.0;
    double slave_mass = kInf, master_mass = kInf;
    for (int j = 0; j < 4; ++j) {
      const int a = slave_nodes_[j], b = master_nodes_[j];
      const double ws = slave_weights_[j], wm = master_weights_[j];
      inverse_mass += ws * ws * InverseMass(mass[a]) + wm * wm * InverseMass(mass[b]);
      rvx += ws * vx[a] - wm * vx[b];
      rvy += ws * vy[a] - wm * vy[b];
      slave_mass = std::min(slave_mass, mass[a]);
      master_mass = std::min(master_mass, mass[b]);
    }
    const SplineContactPoint& p = point_;
    const int segment = pass.master.segment_after[p.master_span];
    ContactKinematics point;
    point.penetration = -p.gap;
    point.nx = p.nx, point.ny = p.ny;
    point.rvx = rvx, point.rvy = rvy;
    point.inverse_mass_sum = inverse_mass;
    law.Apply(law.SegmentStiffness(pass.master, segment, slave_mass, master_mass),
              point,
              dt,
              pass.PointSpring(),
              &slot);
    slot.segment = segment;
    slot.xi = p.s;
  } else {
    pass.ReleasePointSpring();
  }
  pass.ReleaseIdleNodeSprings();
}

void SplineContact::Scatter(const ContactPass& pass, solver::ForceLog* forces) const {
  const ContactSlot& slot = pass.point_slot;
  // f n on the slave's control points by their B-spline weights, -f n on the master's: the
  // exact -grad of the penalty (spline_surface.h); friction the same way at the curve points.
  const double gx = slot.fnx + slot.ftx, gy = slot.fny + slot.fty;
  for (int j = 0; j < 4; ++j) {
    const double ws = slave_weights_[j], wm = master_weights_[j];
    forces->Add(slave_nodes_[j], ws * gx, ws * gy);
    forces->Add(master_nodes_[j], -(wm * gx), -(wm * gy));
  }
}

void SplineContact::Save(CheckpointWriter* out) const {
  out->Put(slave_spline_.offset);
  out->Put(master_spline_.offset);
  out->Put(found_);
  out->Put(point_);
}

void SplineContact::Load(CheckpointReader* in) {
  slave_spline_.offset = in->Get<double>();
  master_spline_.offset = in->Get<double>();
  found_ = in->Get<bool>();
  point_ = in->Get<SplineContactPoint>();
}

}  // namespace spallkit::sim::contact
