#include "sim/contact/arc_blend_contact.h"

#include <ceres/jet.h>

#include <algorithm>
#include <cmath>

namespace spallkit::sim::contact {

namespace {
// A closest point this close to a span's end (chord parameter) still counts as in span: where the
// contact direction passes exactly through a node (a rim node on the load line at t = 0), rounding
// would otherwise put it outside both arcs and drop the contact to the nodes, whose stiffness per
// node differs from the arc's.
constexpr double kSpanTolerance = 1e-9;
// Below this total blend weight (points within ~1e-6 of a span end, the weight ~ xi^2) the
// weights' gradient would divide rounding noise by ~0; the deepest point then acts alone.
constexpr double kMinBlendWeight = 1e-24;

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
// Where a ridge point is in its wedge, 0 .. 1 (FindCandidates' values, here on Jets for the
// gradient): how far the closest point on the arc before the ridge falls past its end, against how
// far the one on the next arc falls before its start. Slave ridge (master_ridge false) at node
// s[2..3] between the arc s[0..3] (curvature ks) and the next slave arc s[2..3] -> t (kt), both
// against master m; master ridge at m[2..3] between arc m and the next master arc m[2..3] -> t
// (kt), both against the slave arc s.
template <typename T>
T RidgeWedge(
    bool master_ridge, const T s[4], double ks, const T m[4], double km, const T t[2], double kt) {
  const T* ridge_arc = master_ridge ? m : s;
  const T next[4] = {ridge_arc[2], ridge_arc[3], t[0], t[1]};
  ArcPair<T> a, b;
  ArcClosestPoints(s, ks, m, km, &a);
  if (master_ridge)
    ArcClosestPoints(s, ks, next, kt, &b);
  else
    ArcClosestPoints(next, kt, m, km, &b);
  const T past = (master_ridge ? a.xi_master : a.xi) - 1.0;
  return past / (past - (master_ridge ? b.xi_master : b.xi));
}

}  // namespace

ArcBlendContact::ArcBlendContact(const ContactPass& pass) {
  const ContactSurface& slave = pass.slave;
  const int n = slave.num_nodes(), m = slave.num_segments();
  candidates_.reserve(4 * m);  // no allocation in the time loop
  blend_.reserve(4 * m);
  rim_node_.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    const int before = slave.segment_before[i], after = slave.segment_after[i];
    rim_node_[i] = before >= 0 && after >= 0 && slave.segment_curvature[before] > 0.0 &&
                   slave.segment_curvature[after] > 0.0;
  }
  if (pass.master.curved()) {
    master_arcs_.assign(pass.master.num_segments(), Arc<double>{});
    master_arc_stamp_.assign(pass.master.num_segments(), -1);
  }
}

void ArcBlendContact::Find(ContactPass& pass, const double* x, const double* y) {
  std::fill(pass.node_owned.begin(), pass.node_owned.end(), 0);
  candidates_.clear();
  blend_.clear();
  ++stamp_;
  FindCandidates(pass, x, y);
  ChainDeepest(pass);
  if (!blend_.empty()) Blend(pass, x, y);
}

void ArcBlendContact::FindCandidates(ContactPass& pass, const double* x, const double* y) {
  const ContactSurface& slave = pass.slave;
  const ContactSurface& master = pass.master;
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
      if (master_arc_stamp_[m] != stamp_) {  // once per step
        master_arcs_[m] = ArcThrough(mp[0], mp[1], mp[2], mp[3], master.segment_curvature[m]);
        master_arc_stamp_[m] = stamp_;
      }
      return &master_arcs_[m];
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
      Point c;
      c.at = g;
      c.slave_segment = slave_segment;
      c.master_segment = m;
      c.slave_node = slave_node;
      c.master_node = master_node;
      c.third_node = third_node;
      c.third_curvature = third_curvature;
      c.wedge = wedge;
      candidates_.push_back(c);
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
}

void ArcBlendContact::ChainDeepest(ContactPass& pass) {
  const ContactSurface& slave = pass.slave;
  // One contact per pass: the deepest point and the points of the slave arcs chained to it (a
  // dented node gives two, see arc_blend_contact.h). With none (the closest direction falls on a
  // kink between two deformed arcs, or a spall faces the master) every node keeps node contact.
  const std::vector<Point>& cand = candidates_;
  if (cand.empty()) return;
  size_t deepest = 0;
  for (size_t i = 1; i < cand.size(); ++i)
    if (cand[i].at.gap < cand[deepest].at.gap) deepest = i;
  auto has_point = [&](int k) {
    for (const Point& c : cand)
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
  for (const Point& c : cand)
    if (in_chain(c.slave_segment)) blend_.push_back(c);
  // Blend shares weights within the points of one slave arc or ridge node, taken as a
  // run: a ridge point is filed under the arc before its node but found while searching the arc
  // after it, so order the blend by that key (insertion sort: a handful of points, no allocation).
  auto key = [](const Point& c) { return 2 * c.slave_segment + (c.slave_node ? 1 : 0); };
  std::vector<Point>& blend = blend_;
  for (size_t i = 1; i < blend.size(); ++i)
    for (size_t j = i; j > 0 && key(blend[j - 1]) > key(blend[j]); --j)
      std::swap(blend[j - 1], blend[j]);
  // Nodes the arc contact stands for: the blend's arcs' ends, and every node between two convex
  // arcs (an interior point of the smooth rim; node contact there would count the overlap twice).
  for (const Point& b : blend_) {
    pass.node_owned[slave.segment_a[b.slave_segment]] = 1;
    pass.node_owned[slave.segment_b[b.slave_segment]] = 1;
  }
  for (int i = 0; i < slave.num_nodes(); ++i) pass.node_owned[i] |= rim_node_[i];
}

void ArcBlendContact::Blend(const ContactPass& pass, const double* x, const double* y) {
  // p = sum w_c p_c / sum w_c over the blend's points, w_c = S_c omega_c: the slave span factor
  // S_c = SpanWeight(xi_c) times the point's share of its slave arc's master factors,
  // omega_c = M_c / sum_g M, M_c = SpanWeight(xi_master_c), over the points g of the same slave
  // arc or ridge node (its points on neighbouring master arcs). A ridge point's factor on its
  // node's side is SpanWeight of its place in the wedge.
  // Why the share: with plain products S_c M_c, a slave arc's point crossing a master node has
  // both its points at a master span end, its weight ~ 0 beside a second arc's point near its own
  // end, and the ratio of the two vanishing weights swings over nanometres of motion (200x the
  // penalty stiffness on the 0.25 mm mesh), which creates energy. The share keeps the slave arc's
  // weight whole across the node.
  // The gradient, weights included, by forward-mode automatic differentiation of each point's
  // geometry over its coordinates (ceres::Jet):
  //   dp = (1/W) sum_c [w_c dp_c + (p_c - p) omega_c dS_c + ((p_c - p) S_c - A_g) dM_c / sum_g M],
  //   A_g = sum_{c in g} omega_c (p_c - p) S_c,  W = sum w_c.
  // With that the normal force -f_n grad p is conservative for the blended penalty k p^2 / 2.
  using Jet = ceres::Jet<double, kCoordinates>;
  const ContactSurface& slave = pass.slave;
  const ContactSurface& master = pass.master;
  std::vector<Point>& blend = blend_;
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
      Point& c = blend[i];
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
      const Point& c = blend[i];
      a_g += c.omega * (-c.at.gap - penetration) * SlaveFactor(c.at, c.slave_node, c.wedge);
    }
    for (size_t i = g0; i < g1; ++i) {
      Point& c = blend[i];
      const std::array<int, 4> nodes = Nodes(pass, c);
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
        wedge = RidgeWedge(false, s, ks, m, km, t, c.third_curvature);
      } else if (c.master_node) {
        ArcNodeClosestPoints(s, ks, &m[2], &g);  // the node is the master segment's end b
        wedge = RidgeWedge(true, s, ks, m, km, t, c.third_curvature);
      } else {
        ArcClosestPoints(s, ks, m, km, &g);
      }
      c.weight /= total;
      const double dp = -c.at.gap - penetration;
      const Jet sf = SlaveFactor(g, c.slave_node, wedge),
                mf = MasterFactor(g, c.master_node, wedge);
      const double m_coef = c.master_sum > 0.0 ? (dp * sf.a - a_g) / c.master_sum : 0.0;
      for (int d = 0; d < kCoordinates; ++d) {
        c.grad[d] = -c.weight * g.gap.v[d];
        if (!fixed_weight) c.grad[d] += (dp * c.omega * sf.v[d] + m_coef * mf.v[d]) / total;
      }
    }
  }
}

void ArcBlendContact::Forces(ContactPass& pass,
                             const ContactLaw& law,
                             const fe::NodalState& state,
                             double dt) {
  const ContactSurface& slave = pass.slave;
  const double* x = state.x.data();
  const double* y = state.y.data();
  const double* vx = state.vx.data();
  const double* vy = state.vy.data();
  const double* mass = state.mass.data();
  ContactSlot& slot = pass.point_slot;
  slot = ContactSlot{};
  double penetration = 0.0;
  for (const Point& c : blend_) penetration -= c.weight * c.at.gap;
  if (!blend_.empty() && penetration > 0.0 && penetration <= pass.capture) {
    // Hand-over: the contact walked here from a node.
    for (const Point& c : blend_)
      for (int local : {slave.segment_a[c.slave_segment], slave.segment_b[c.slave_segment]})
        pass.TakeNodeSpring(local);
    // Blended stiffness, mass and normal; relative velocities conjugate to how the forces are
    // spread: the normal one is -dp/dt, the tangential one the arc points' slip.
    double k = 0.0, inverse_mass = 0.0, nx = 0.0, ny = 0.0, vn = 0.0, sx = 0.0, sy = 0.0;
    for (const Point& c : blend_) {
      const std::array<int, 4> nodes = Nodes(pass, c);
      const double ws = c.at.xi, wm = c.at.xi_master;
      k += c.weight * law.SegmentStiffness(pass.master,
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
    ContactKinematics point;
    point.penetration = penetration;
    point.nx = nx, point.ny = ny;
    point.rvx = vn * nx - vt * ny, point.rvy = vn * ny + vt * nx;
    point.inverse_mass_sum = inverse_mass;
    law.Apply(k, point, dt, pass.PointSpring(), &slot);
    slot.segment = blend_.front().master_segment;
    slot.xi = blend_.front().at.xi_master;
  } else {
    pass.ReleasePointSpring();
  }
  pass.ReleaseIdleNodeSprings();
}

std::array<int, 4> ArcBlendContact::Nodes(const ContactPass& pass, const Point& c) {
  const ContactSurface& s = pass.slave;
  const ContactSurface& m = pass.master;
  return {s.nodes[s.segment_a[c.slave_segment]],
          s.nodes[s.segment_b[c.slave_segment]],
          m.nodes[m.segment_a[c.master_segment]],
          m.nodes[m.segment_b[c.master_segment]]};
}

void ArcBlendContact::Scatter(const ContactPass& pass,
                              const double* x,
                              const double* y,
                              solver::ForceLog* forces) const {
  const ContactSlot& slot = pass.point_slot;
  // Normal force -f_n grad p (conservative, Blend); friction at the arc points (it turns the
  // roller), by the blend's weights.
  for (const Point& c : blend_) {
    const std::array<int, 4> nodes = Nodes(pass, c);
    for (int j = 0; j < 4; ++j)
      forces->Add(nodes[j], -(slot.fn * c.grad[2 * j]), -(slot.fn * c.grad[2 * j + 1]));
    if (c.third_node >= 0)
      forces->Add(c.third_node, -(slot.fn * c.grad[8]), -(slot.fn * c.grad[9]));
    const double ftx = c.weight * slot.ftx, fty = c.weight * slot.fty;
    SpreadAtArcPoint(x, y, nodes[0], nodes[1], c.at.xi, c.at.px, c.at.py, ftx, fty, forces);
    SpreadAtArcPoint(
        x, y, nodes[2], nodes[3], c.at.xi_master, c.at.qx, c.at.qy, -ftx, -fty, forces);
  }
}

}  // namespace spallkit::sim::contact
