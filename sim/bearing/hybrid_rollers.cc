#include "sim/bearing/hybrid_rollers.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <sstream>

#include "core/constants.h"
#include "core/error.h"
#include "sim/contact/spline_surface.h"
#include "sim/quasistatic/harris_jones.h"

namespace spallkit::sim {
namespace {

constexpr int kMaxKernel = 64;
// Stick springs per roller: outer race, inner race, leading wall, trailing wall (the notched
// part of the roller), then outer and inner race of the intact part of a partial-length spall.
constexpr int kFrictionSlots = 6;
// Safety factor on the contacts' stable step (the solver scales only the element step).
constexpr double kContactSafety = 0.8;

double Wrap(double a) {  // to (-pi, pi]
  a = std::remainder(a, 2.0 * kPi);
  return a;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// RollerProfile

double RollerProfile::HalfAngle() const {
  return spalled ? std::asin(std::min(1.0, 0.5 * width / radius)) : 0.0;
}

namespace {
// Fillet centre in the spall frame (u lateral, v along the spall axis), u >= 0 side.
void FilletCentre(const RollerProfile& p, double* u, double* v) {
  const double rho = p.edge_radius, a = 0.5 * p.width;
  *u = a + rho;
  *v = std::sqrt(std::max(0.0, (p.radius - rho) * (p.radius - rho) - *u * *u));
}
}  // namespace

double RollerProfile::ContactHalfAngle() const {
  if (!spalled) return 0.0;
  double u, v;
  FilletCentre(*this, &u, &v);
  return std::atan2(u, v);
}

bool RollerProfile::InSpall(double a) const {
  return spalled && std::abs(Wrap(a - angle)) < ContactHalfAngle();
}

void RollerProfile::RimCorners(double cx[2], double cy[2]) const {
  double a, s;
  FilletCentre(*this, &a, &s);
  const double c = std::cos(angle), sn = std::sin(angle);
  // Spall frame: v along the spall direction (c, sn), u lateral (-sn, c).
  for (int k = 0; k < 2; ++k) {
    const double u = k == 0 ? a : -a;
    cx[k] = s * c - u * sn;
    cy[k] = s * sn + u * c;
  }
}

double RollerProfile::Support(double a) const { return SupportPoint(a, nullptr, nullptr); }

double RollerProfile::SupportPoint(double a, double* px, double* py) const {
  const double ux = std::cos(a), uy = std::sin(a);
  double x = radius * ux, y = radius * uy;
  if (InSpall(a)) {
    double cx[2], cy[2];
    RimCorners(cx, cy);
    const int k = cx[0] * ux + cy[0] * uy >= cx[1] * ux + cy[1] * uy ? 0 : 1;
    x = cx[k] + edge_radius * ux, y = cy[k] + edge_radius * uy;
  }
  if (px) *px = x, *py = y;
  return x * ux + y * uy;
}

RollerProfile::Properties RollerProfile::SectionProperties() const {
  const double r = radius;
  Properties p;
  double area = kPi * r * r, moment = 0.0, polar = 0.5 * kPi * r * r * r * r;
  if (spalled) {
    // Spall region in its own frame: v in [r - h, r], |u| < min(w/2, sqrt(r^2 - v^2)).
    // With fillets the removed strip at v is wider above the fillet centre (v > v_f): up to
    // the fillet arc u = u_f - sqrt(rho^2 - (v - v_f)^2), then the circle.
    const int n = 20000;
    const double v0 = r - depth, dv = depth / n;
    double uf, vf;
    FilletCentre(*this, &uf, &vf);
    double as = 0.0, ms = 0.0, is = 0.0;
    for (int i = 0; i < n; ++i) {
      const double v = v0 + (i + 0.5) * dv;
      const double circle = std::sqrt(std::max(0.0, r * r - v * v));
      double wall = 0.5 * width;
      if (edge_radius > 0 && v > vf) {
        const double dz = v - vf;
        wall = dz < edge_radius ? uf - std::sqrt(edge_radius * edge_radius - dz * dz) : circle;
      }
      const double a = std::min(wall, circle);
      as += 2.0 * a * dv;
      ms += 2.0 * a * v * dv;
      is += (2.0 * a * v * v + 2.0 / 3.0 * a * a * a) * dv;
    }
    area -= as, moment -= ms, polar -= is;
  }
  const double vc = moment / area;  // along the spall direction
  p.area = area;
  p.cx = vc * std::cos(angle);
  p.cy = vc * std::sin(angle);
  p.polar = polar - area * vc * vc;
  return p;
}

// ---------------------------------------------------------------------------------------------
// HybridOptions

bool HybridOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* m) {
    if (error) *error = m;
    return false;
  };
  if (!(palmgren_coefficient > 0)) return fail("hybrid model: palmgren_coefficient must be > 0");
  if (!(contact_damping_ratio >= 0 && contact_damping_ratio <= 1))
    return fail("hybrid model: contact_damping_ratio must be in [0, 1]");
  if (!(tangential_stiffness_ratio > 0))
    return fail("hybrid model: tangential_stiffness_ratio must be > 0");
  if (!(cage_stiffness_n_per_m > 0))
    return fail("hybrid model: cage_stiffness_n_per_m must be > 0");
  if (!(spread_half_width_m >= 0)) return fail("hybrid model: spread_half_width_m must be >= 0");
  return true;
}

// ---------------------------------------------------------------------------------------------
// HybridRollers

HybridRollers::HybridRollers(const Scene& scene,
                             const BearingMesh& housing,
                             const fe::NodalState& state,
                             const HybridOptions& options,
                             const CageGuideOptions& cage_guide)
    : scene_(scene), options_(options), cage_guide_(cage_guide) {
  std::string err;
  if (!options_.IsValid(&err)) throw InputError(err);
  if (!cage_guide_.IsValid(&err)) throw InputError(err);
  const SceneGeometry& g = scene_.geometry;
  const int z = g.bearing.num_elements;
  const double t = g.thickness_m;
  const double omega = scene_.operation.inner_ring_speed_rad_s;
  const double ramp = scene_.operation.ramp_s;
  angle_ = solver::RampedRotation(omega, ramp);
  speed_ = solver::RampedSpeed(omega, ramp);
  const double load = scene_.operation.radial_load_n;
  load_ = solver::LinearRamp(-load, scene_.operation.load_ramp_s);
  outer_radius_ = housing.outer_raceway_radius_m;
  inner_radius_ = housing.inner_raceway_radius_m;
  pocket_half_width_ = 0.5 * (g.bearing.element_diameter_m + g.pocket_clearance_m);
  pitch_radius_ = housing.pitch_radius_m;
  k_c_ = PalmgrenContactStiffness(t, options_.palmgren_coefficient);

  // Rollers: exact profiles, mass properties, initial pose (centred, pitch circle).
  const double rho_r = scene_.materials.roller.density_kg_m3;
  for (int j = 0; j < z; ++j) {
    RollerProfile p;
    p.radius = housing.roller_radius_m;
    const double phi = housing.roller_angles_rad[j];
    for (const Defect& d : scene_.defects)
      if (d.roller == j) {
        if (!(d.depth_m < p.radius) || !(d.width_m < 2.0 * p.radius))
          throw InputError("defects: the spall of roller " + std::to_string(j) +
                           " must be narrower than the roller diameter and shallower than its "
                           "radius");
        p.spalled = true, p.width = d.width_m, p.depth = d.depth_m, p.angle = phi + d.angle_rad;
        p.edge_radius = d.edge_radius_m;
        if (!(p.edge_radius >= 0) || !(p.radius - p.edge_radius > 0.5 * p.width + p.edge_radius) ||
            !(p.edge_radius < p.depth))
          throw InputError("defects: edge_radius_mm of roller " + std::to_string(j) +
                           " must be >= 0, smaller than the spall depth, and leave the fillet "
                           "inside the roller");
      }
    // A spall shorter than the roller: the spalled length fraction f has the notched section,
    // the rest the full circle; mass properties are the length-weighted mixture.
    double f = 1.0;
    for (const Defect& d : scene_.defects)
      if (d.roller == j && d.length_m > 0) f = std::min(1.0, d.length_m / t);
    const RollerProfile::Properties sp = p.SectionProperties();
    const double a_c = kPi * p.radius * p.radius, polar_c = 0.5 * a_c * p.radius * p.radius;
    const double area = f * sp.area + (1 - f) * a_c;
    const double cx = f * sp.area * sp.cx / area, cy = f * sp.area * sp.cy / area;
    const double polar =
        f * (sp.polar + sp.area * ((sp.cx - cx) * (sp.cx - cx) + (sp.cy - cy) * (sp.cy - cy))) +
        (1 - f) * (polar_c + a_c * (cx * cx + cy * cy));
    profiles_.push_back(p);
    intact_profiles_.push_back(p);
    intact_profiles_.back().spalled = false;
    spall_fraction_.push_back(p.spalled ? f : 1.0);
    roller_mass_.push_back(rho_r * t * area);
    roller_inertia_.push_back(rho_r * t * polar);
    centroid_x_.push_back(cx);
    centroid_y_.push_back(cy);
    pocket_angle_.push_back(phi);
    Body b;
    b.x = housing.pitch_radius_m * std::cos(phi) + cx;
    b.y = housing.pitch_radius_m * std::sin(phi) + cy;
    rollers_.push_back(b);
  }

  // Cage webs: the annulus minus the Z pockets (polar-grid quadrature).
  {
    const double rci = 0.5 * g.cage_inner_diameter_m, rco = 0.5 * g.cage_outer_diameter_m;
    const int nr = 200, nt = 400 * z;
    const double dr = (rco - rci) / nr, dth = 2 * kPi / nt;
    double area = 0, polar = 0;
    for (int i = 0; i < nr; ++i) {
      const double r = rci + (i + 0.5) * dr;
      for (int k = 0; k < nt; ++k) {
        const double th = (k + 0.5) * dth;
        const double rel = th - pocket_angle_[0];
        const double d = Wrap(rel - 2 * kPi / z * std::round(rel / (2 * kPi / z)));
        if (std::cos(d) > 0 && std::abs(r * std::sin(d)) < pocket_half_width_) continue;
        area += r * dr * dth;
        polar += r * r * r * dr * dth;
      }
    }
    cage_mass_ = scene_.materials.cage.density_kg_m3 * t * area;
    cage_inertia_ = scene_.materials.cage.density_kg_m3 * t * polar;
  }
  shaft_mass_ = scene_.materials.inner_ring.density_kg_m3 * g.ring_width_m * kPi *
                (inner_radius_ * inner_radius_ -
                 0.25 * g.inner_ring_bore_diameter_m * g.inner_ring_bore_diameter_m);

  // Outer raceway nodes, sorted by reference angle; uniform spacing required.
  {
    auto it = housing.mesh.curves.find("outer_ring.raceway");
    if (it == housing.mesh.curves.end())
      throw InputError("hybrid model: housing mesh has no 'outer_ring.raceway'");
    std::vector<std::pair<double, int>> nodes;
    for (int id : it->second.nodes)
      nodes.emplace_back(std::atan2(housing.mesh.y[id], housing.mesh.x[id]), id);
    std::sort(nodes.begin(), nodes.end());
    const int n = static_cast<int>(nodes.size());
    if (n < 8) throw InputError("hybrid model: outer raceway has fewer than 8 nodes");
    ring_dtheta_ = 2 * kPi / n;
    ring_theta0_ = nodes[0].first;
    for (int k = 0; k < n; ++k) {
      const double expect = ring_theta0_ + k * ring_dtheta_;
      if (std::abs(nodes[k].first - expect) > 1e-6 * ring_dtheta_ + 1e-9)
        throw InputError("hybrid model: outer raceway nodes are not uniformly spaced");
      const int id = nodes[k].second;
      ring_nodes_.push_back(id);
      const double rr = std::hypot(housing.mesh.x[id], housing.mesh.y[id]);
      ring_ex_.push_back(housing.mesh.x[id] / rr);
      ring_ey_.push_back(housing.mesh.y[id] / rr);
    }
    const double spacing = outer_radius_ * ring_dtheta_;
    spread_ = options_.spread_half_width_m > 0 ? options_.spread_half_width_m
                                               : std::max(1e-3, 2.0 * spacing);
    if (2 * static_cast<int>(std::ceil(spread_ / spacing)) + 1 > kMaxKernel)
      throw InputError("hybrid model: spread_half_width_m covers more than 64 raceway nodes");
  }

  // Ring side of an outer-race contact: the gap is delta = (roller) - sum_i w_i u_i, so the
  // contact couples the roller with the raceway nodes through K = k w~ w~^T, w~ = (1, -w). Its
  // one non-zero mode has omega^2 = k (1/m_roller + sum_i w_i^2 / m_i): the ring acts as ONE
  // body of effective mass m_ring = 1 / sum_i w_i^2/m_i (the kernel's nodes, weighted), taken at
  // its smallest over the kernel's positions between two nodes.
  {
    int idx[kMaxKernel];
    double w[kMaxKernel], s_max = 0.0;
    for (int s = 0; s <= 10; ++s) {
      const int n = Kernel(ring_theta0_ + 0.05 * s * ring_dtheta_, idx, w);
      for (int k = 0; k < static_cast<int>(ring_nodes_.size()); k += 1) {
        // every kernel position around the ring (node masses may differ near the seat)
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
          const int id = ring_nodes_[(idx[i] + k) % ring_nodes_.size()];
          sum += w[i] * w[i] / state.mass[id];
        }
        s_max = std::max(s_max, sum);
      }
    }
    ring_mass_ = 1.0 / s_max;
  }
  // Stable step of the contacts (the normal and the stick spring act together; stiffness at
  // twice the radial load, a bound on impacts): each contact is a two-body oscillator with
  // damping zeta of ITS critical value (reduced mass), so the central-difference limit is
  // 2/omega (sqrt(1 + zeta^2) - zeta) with
  //  - roller side: both races' springs on the roller's rim (effective mass m/3: translation
  //    plus rotation for a tangential force on a disc), omega^2 = 2 k (3/m_r);
  //  - ring side: omega^2 = k (3/m_r + 1/m_ring) for one contact on the ring's kernel nodes.
  {
    const double q = 2.0 * std::max(load, 1000.0);
    const double delta = std::pow(q / k_c_, 0.9);
    const double kn = 10.0 / 9.0 * q / delta;
    double m_min = roller_mass_[0];
    for (double m : roller_mass_) m_min = std::min(m_min, m);
    const double zeta = options_.contact_damping_ratio;
    const double k = kn * (1.0 + options_.tangential_stiffness_ratio);
    auto limit = [zeta](double omega) { return 2.0 / omega * (std::sqrt(1 + zeta * zeta) - zeta); };
    roller_dt_ = limit(std::sqrt(2.0 * k * 3.0 / m_min));
    ring_dt_ = limit(std::sqrt(k * (3.0 / m_min + 1.0 / ring_mass_)));
    dt_limit_ = kContactSafety * std::min(roller_dt_, ring_dt_);
  }

  friction_.assign(kFrictionSlots * z, 0.0);
  outer_force_.assign(z, 0.0);
  inner_force_.assign(z, 0.0);
  cage_force_.assign(z, 0.0);
  fx_.assign(z, 0.0);
  fy_.assign(z, 0.0);
  torque_.assign(z, 0.0);
}

int HybridRollers::Kernel(double th, int* idx, double* w, double* dw) const {
  // w_k = a_k / S with a_k = B3(u_k), u_k = 2 R0 (theta_k - th) / L (the cubic B-spline, support
  // |u| < 2, i.e. half-width L), S = sum a_k; so dw_k/dth = (a_k' - w_k S') / S with
  // a_k' = B3'(u_k) (-2 R0 / L). B3 is C2: the weights change smoothly as a contact crosses a node
  // (a parabola 1 - s^2 has a kink at its ends; it made the sensor 3x louder,
  // docs/BEARING_MODEL.md).
  const int n = static_cast<int>(ring_nodes_.size());
  const double spacing = outer_radius_ * ring_dtheta_;
  const int m = static_cast<int>(std::ceil(spread_ / spacing));
  const long k0 = std::lround((th - ring_theta0_) / ring_dtheta_);
  const double du_dth = -2.0 * outer_radius_ / spread_;
  int count = 0;
  double sum = 0.0, dsum = 0.0;
  for (long k = k0 - m; k <= k0 + m; ++k) {
    const double u = 2.0 * outer_radius_ * (ring_theta0_ + k * ring_dtheta_ - th) / spread_;
    double da;
    const double a = contact::CubicBSpline(u, &da);
    if (a <= 0.0) continue;
    idx[count] = static_cast<int>(((k % n) + n) % n);
    w[count] = a;
    if (dw) dw[count] = da * du_dth, dsum += dw[count];
    sum += a;
    ++count;
  }
  for (int i = 0; i < count; ++i) {
    w[i] /= sum;
    if (dw) dw[i] = (dw[i] - w[i] * dsum) / sum;
  }
  return count;
}

double HybridRollers::RaceRadius(const fe::NodalState& s, double th, double* slope) const {
  int idx[kMaxKernel];
  double w[kMaxKernel], dw[kMaxKernel];
  const int n = Kernel(th, idx, w, slope ? dw : nullptr);
  double u = 0.0, du = 0.0;
  for (int i = 0; i < n; ++i) {
    const int id = ring_nodes_[idx[i]];
    const double ui =
        (s.x[id] - s.x0[id]) * ring_ex_[idx[i]] + (s.y[id] - s.y0[id]) * ring_ey_[idx[i]];
    u += w[i] * ui;
    if (slope) du += dw[i] * ui;
  }
  if (slope) *slope = du;
  return outer_radius_ + u;
}

void HybridRollers::RollerCentre(int j, double* x, double* y) const {
  const Body& b = rollers_[j];
  const double c = std::cos(b.angle), s = std::sin(b.angle);
  *x = b.x - (c * centroid_x_[j] - s * centroid_y_[j]);
  *y = b.y - (s * centroid_x_[j] + c * centroid_y_[j]);
}

int HybridRollers::RacePoints(int j, int which, const RollerProfile& p, Point out[2]) const {
  // Positions only; the outer race radius is filled in by the caller (needs the nodal state).
  const Body& b = rollers_[j];
  double cx, cy;
  RollerCentre(j, &cx, &cy);
  double dx, dy;  // unit direction from the roller centre towards the race contact
  if (which == 0) {
    const double d = std::hypot(cx, cy);
    dx = cx / d, dy = cy / d;
  } else {
    const double ex = shaft_.x - cx, ey = shaft_.y - cy, d = std::hypot(ex, ey);
    dx = ex / d, dy = ey / d;
  }
  const double a = std::atan2(dy, dx) - b.angle;
  if (!p.InSpall(a)) {
    out[0] = {cx + p.radius * dx, cy + p.radius * dy, -dx, -dy, 0.0};
    return 1;
  }
  // Rim edges: the fillet centres (the corners for sharp edges); the caller offsets them by
  // the fillet radius along the race normal through each.
  double kx[2], ky[2];
  p.RimCorners(kx, ky);
  const double c = std::cos(b.angle), s = std::sin(b.angle);
  for (int k = 0; k < 2; ++k)
    out[k] = {cx + c * kx[k] - s * ky[k], cy + s * kx[k] + c * ky[k], -dx, -dy, 0.0};
  return 2;
}

void HybridRollers::AddForces(fe::NodalState& state, double t, double dt) {
  const int z = num_rollers();
  const double zeta = options_.contact_damping_ratio;
  const double mu_s = scene_.friction.mu_static, mu_d = scene_.friction.mu_dynamic,
               decay = scene_.friction.decay_s_m;
  const double omega_s = speed_(t);
  double shaft_fx = 0, shaft_fy = 0, shaft_torque = 0, cage_fx = 0, cage_fy = 0, cage_torque = 0;
  double potential = 0.0;
  std::fill(fx_.begin(), fx_.end(), 0.0);
  std::fill(fy_.begin(), fy_.end(), 0.0);
  std::fill(torque_.begin(), torque_.end(), 0.0);

  // Counter bodies: 0 outer ring (FE nodes), 1 shaft, 2 cage.
  auto counter_velocity = [&](int body, double px, double py, double* vx, double* vy) {
    if (body == 0) {
      int idx[kMaxKernel];
      double w[kMaxKernel];
      const int n = Kernel(std::atan2(py, px), idx, w);
      *vx = *vy = 0.0;
      for (int i = 0; i < n; ++i) {
        const int id = ring_nodes_[idx[i]];
        *vx += w[i] * state.vx[id], *vy += w[i] * state.vy[id];
      }
    } else if (body == 1) {
      *vx = shaft_.vx - omega_s * (py - shaft_.y);
      *vy = shaft_.vy + omega_s * (px - shaft_.x);
    } else {
      *vx = cage_.vx - cage_.omega * (py - cage_.y);
      *vy = cage_.vy + cage_.omega * (px - cage_.x);
    }
  };
  auto apply_counter = [&](int body, double px, double py, double fx, double fy) {
    if (body == 0) {
      int idx[kMaxKernel];
      double w[kMaxKernel];
      const int n = Kernel(std::atan2(py, px), idx, w);
      for (int i = 0; i < n; ++i) {
        const int id = ring_nodes_[idx[i]];
        state.fx[id] += w[i] * fx, state.fy[id] += w[i] * fy;
      }
    } else if (body == 1) {
      shaft_fx += fx, shaft_fy += fy;
      shaft_torque += (px - shaft_.x) * fy - (py - shaft_.y) * fx;
    } else {
      cage_fx += fx, cage_fy += fy;
      cage_torque += (px - cage_.x) * fy - (py - cage_.y) * fx;
    }
  };

  // One contact (1 or 2 points) of roller j with a counter body; returns the normal force.
  // `scale`: the share of the Palmgren stiffness (the contact's length fraction).
  auto contact = [&](int j,
                     int body,
                     bool palmgren,
                     Point* pts,
                     int npts,
                     double* spring,
                     double scale = 1.0) {
    const Body& b = rollers_[j];
    // Damping of each contact: a fraction of ITS critical value, i.e. with the reduced mass of
    // the roller and the counter body (LS-DYNA's viscous contact damping does the same with the
    // slave and master nodal masses); for the ring, its kernel's effective mass.
    const double m_counter = body == 0 ? ring_mass_ : body == 1 ? shaft_mass_ : cage_mass_;
    const double m = 1.0 / (1.0 / roller_mass_[j] + 1.0 / m_counter);
    const double m_t = 1.0 / (3.0 / roller_mass_[j] + 1.0 / m_counter);
    double q[2] = {0, 0}, q_total = 0, kn_total = 0, vt_acc = 0;
    double tx = -pts[0].ny, ty = pts[0].nx;
    for (int k = 0; k < npts; ++k) {
      const Point& p = pts[k];
      if (!(p.delta > 0)) continue;
      double qe, kn;
      if (palmgren) {
        qe = scale * k_c_ * std::pow(p.delta, 10.0 / 9.0);
        kn = 10.0 / 9.0 * qe / p.delta;
        potential += qe * p.delta * (9.0 / 19.0);
      } else {
        kn = options_.cage_stiffness_n_per_m;
        qe = kn * p.delta;
        potential += 0.5 * qe * p.delta;
      }
      double vx, vy;
      counter_velocity(body, p.px, p.py, &vx, &vy);
      const double rvx = b.vx - b.omega * (p.py - b.y) - vx;
      const double rvy = b.vy + b.omega * (p.px - b.x) - vy;
      const double rate = -(rvx * p.nx + rvy * p.ny);  // d delta / dt
      const double c = 2.0 * zeta * std::sqrt(kn * m);
      q[k] = std::max(0.0, qe + c * rate);
      damping_work_ += (q[k] - qe) * rate * dt;
      q_total += q[k];
      kn_total += kn;
      vt_acc += q[k] * (rvx * tx + rvy * ty);
    }
    if (!(q_total > 0)) {
      *spring = 0.0;
      return 0.0;
    }
    // Regularised Coulomb friction with a stick spring.
    const double vt = vt_acc / q_total;
    const double mu = mu_d + (mu_s - mu_d) * std::exp(-decay * std::abs(vt));
    const double cap = mu * q_total;
    const double kt = options_.tangential_stiffness_ratio * kn_total;
    const double ct = 2.0 * zeta * std::sqrt(kt * m_t);
    const double fs = std::clamp(*spring - kt * vt * dt, -cap, cap);
    const double f = std::clamp(fs - ct * vt, -cap, cap);
    *spring = fs;
    friction_work_ -= f * vt * dt;
    for (int k = 0; k < npts; ++k) {
      if (!(q[k] > 0)) continue;
      const Point& p = pts[k];
      const double ft = f * q[k] / q_total;
      const double fx = q[k] * p.nx + ft * tx, fy = q[k] * p.ny + ft * ty;
      fx_[j] += fx, fy_[j] += fy;
      torque_[j] += (p.px - b.x) * fy - (p.py - b.y) * fx;
      apply_counter(body, p.px, p.py, -fx, -fy);
    }
    return q_total;
  };

  const double cc = std::cos(cage_.angle), cs = std::sin(cage_.angle);
  // Both race contacts of roller j for one profile (the notched or, for the intact part of a
  // partial-length spall, the full circle) carrying `scale` of the Palmgren stiffness; the
  // stick springs are friction_[slot], friction_[slot + 1]. Adds to outer_force_/inner_force_.
  auto race_contacts = [&](int j, const RollerProfile& prof, double scale, int slot) {
    Point pts[2];
    // Outer race. A profile point is a circle of radius rad around a centre q (the roller's
    // circle, or a rim fillet: its centre and radius, a corner with radius 0); its gap is
    // delta = |q| + rad - R(theta_q). The force on the roller is -Q grad_q delta, i.e. along the
    // normal of the DEFORMED raceway, e_q - (R'/|q|) t_q: with the radial normal alone a roller
    // moving along a sloped (loaded) raceway would change delta without work (energy leak).
    // It acts through q (no torque about a circle centre) at the surface point q - rad n.
    const double rho = prof.edge_radius;
    int n = RacePoints(j, 0, prof, pts);
    double qx[2], qy[2], rad[2];
    if (n == 1) {
      RollerCentre(j, &qx[0], &qy[0]);
      rad[0] = prof.radius;
    } else {
      for (int k = 0; k < 2; ++k) qx[k] = pts[k].px, qy[k] = pts[k].py, rad[k] = rho;
    }
    for (int k = 0; k < n; ++k) {
      const double d = std::hypot(qx[k], qy[k]);
      const double ex = qx[k] / d, ey = qy[k] / d;
      double slope;
      const double race = RaceRadius(state, std::atan2(qy[k], qx[k]), &slope);
      const double gx = ex + slope / d * ey, gy = ey - slope / d * ex;  // e - (R'/d) t
      const double g = std::hypot(gx, gy);
      pts[k].nx = -gx / g, pts[k].ny = -gy / g;
      pts[k].px = qx[k] - rad[k] * pts[k].nx, pts[k].py = qy[k] - rad[k] * pts[k].ny;
      pts[k].delta = d + rad[k] - race;
    }
    outer_force_[j] += contact(j, 0, true, pts, n, &friction_[slot], scale);
    // Inner race (rigid ring on the shaft).
    n = RacePoints(j, 1, prof, pts);
    for (int k = 0; k < n; ++k) {
      const double ex = pts[k].px - shaft_.x, ey = pts[k].py - shaft_.y, d = std::hypot(ex, ey);
      if (n == 2) {  // rim edge: normal through the fillet centre, surface point rho closer
        pts[k].nx = ex / d, pts[k].ny = ey / d;
        pts[k].px -= rho * pts[k].nx, pts[k].py -= rho * pts[k].ny;
        pts[k].delta = inner_radius_ - (d - rho);
      } else {
        pts[k].delta = inner_radius_ - d;
      }
    }
    inner_force_[j] += contact(j, 1, true, pts, n, &friction_[slot + 1], scale);
  };

  for (int j = 0; j < z; ++j) {
    const double f = spall_fraction_[j];
    outer_force_[j] = inner_force_[j] = 0.0;
    race_contacts(j, profiles_[j], f, kFrictionSlots * j);
    const RollerProfile& circle = intact_profiles_[j];
    if (f < 1.0) race_contacts(j, circle, 1.0 - f, kFrictionSlots * j + 4);
    // Cage pocket walls: straight lines +-W/2 from the pocket's centre line.
    double cx, cy;
    RollerCentre(j, &cx, &cy);
    const double psi = pocket_angle_[j] + cage_.angle;
    const double twx = -std::sin(psi), twy = std::cos(psi);
    const double lateral = (cx - cage_.x) * twx + (cy - cage_.y) * twy;
    const double a_lead = psi + 0.5 * kPi - rollers_[j].angle;
    // The force acts at the profile's extreme point towards the wall (a rim edge when the spall
    // faces it), so that its torque matches the gap's dependence on the roller's angle.
    double lx, ly, kx, ky;
    // (The intact part of a partial-length spall reaches further than the notched part.)
    const RollerProfile& wall_prof = f < 1.0 ? circle : profiles_[j];
    const double h_lead = wall_prof.SupportPoint(a_lead, &lx, &ly);
    const double h_trail = wall_prof.SupportPoint(a_lead + kPi, &kx, &ky);
    const double rc = std::cos(rollers_[j].angle), rs = std::sin(rollers_[j].angle);
    Point lead{cx + rc * lx - rs * ly,
               cy + rs * lx + rc * ly,
               -twx,
               -twy,
               lateral + h_lead - pocket_half_width_};
    Point trail{cx + rc * kx - rs * ky,
                cy + rs * kx + rc * ky,
                twx,
                twy,
                -lateral + h_trail - pocket_half_width_};
    (void)cc, (void)cs;
    cage_force_[j] = contact(j, 2, false, &lead, 1, &friction_[kFrictionSlots * j + 2]) +
                     contact(j, 2, false, &trail, 1, &friction_[kFrictionSlots * j + 3]);
    // Radial retention (roller-guided cage): the pocket keeps the roller within
    // +-radial_play of the pitch radius of the cage frame, else the cage could drift
    // sideways with the rollers sliding along their orbits (walls alone allow that mode).
    {
      const double ex = std::cos(psi), ey = std::sin(psi);
      const double radial = (cx - cage_.x) * ex + (cy - cage_.y) * ey - pitch_radius_;
      const double q_signed =
          cage_guide_.RadialForce(radial, &potential);  // on the roller, along e
      if (q_signed != 0.0) {
        const double q = std::abs(q_signed);
        const double fx = q_signed * ex, fy = q_signed * ey;
        fx_[j] += fx, fy_[j] += fy;
        torque_[j] += (cx - rollers_[j].x) * fy - (cy - rollers_[j].y) * fx;
        apply_counter(2, cx, cy, -fx, -fy);
        cage_force_[j] += q;
      }
    }
  }
  potential_ = potential;

  // Central-difference update of the rigid bodies (the solver's scheme and step).
  const double dt_avg = 0.5 * (dt_prev_ + dt);
  double kinetic = 0.0;
  for (int j = 0; j < z; ++j) {
    Body& b = rollers_[j];
    b.vx += dt_avg * fx_[j] / roller_mass_[j];
    b.vy += dt_avg * fy_[j] / roller_mass_[j];
    b.omega += dt_avg * torque_[j] / roller_inertia_[j];
    b.x += dt * b.vx, b.y += dt * b.vy, b.angle += dt * b.omega;
    kinetic += 0.5 * roller_mass_[j] * (b.vx * b.vx + b.vy * b.vy) +
               0.5 * roller_inertia_[j] * b.omega * b.omega;
  }
  cage_.vx += dt_avg * cage_fx / cage_mass_;
  cage_.vy += dt_avg * cage_fy / cage_mass_;
  cage_.omega += dt_avg * cage_torque / cage_inertia_;
  cage_.x += dt * cage_.vx, cage_.y += dt * cage_.vy, cage_.angle += dt * cage_.omega;
  kinetic += 0.5 * cage_mass_ * (cage_.vx * cage_.vx + cage_.vy * cage_.vy) +
             0.5 * cage_inertia_ * cage_.omega * cage_.omega;
  const double load = load_(t);
  const double vy_old = shaft_.vy;
  shaft_.vx += dt_avg * shaft_fx / shaft_mass_;
  shaft_.vy += dt_avg * (shaft_fy + load) / shaft_mass_;
  shaft_.x += dt * shaft_.vx, shaft_.y += dt * shaft_.vy;
  shaft_.angle = angle_(t + dt);
  shaft_.omega = speed_(t + 0.5 * dt);
  kinetic += 0.5 * shaft_mass_ * (shaft_.vx * shaft_.vx + shaft_.vy * shaft_.vy);
  kinetic_ = kinetic;
  // Load work over the half steps around t^n; drive torque = -(contact torque on the shaft).
  external_work_ += load * dt_avg * 0.5 * (vy_old + shaft_.vy);
  external_work_ += -shaft_torque * omega_s * dt_avg;
  dt_prev_ = dt;
}

double HybridRollers::StableTimeStep(const fe::NodalState& /*state*/) const { return dt_limit_; }

std::string HybridRollers::SaveState() const {
  std::vector<double> v;
  auto put_body = [&](const Body& b) {
    for (double x : {b.x, b.y, b.angle, b.vx, b.vy, b.omega}) v.push_back(x);
  };
  for (const Body& b : rollers_) put_body(b);
  put_body(cage_);
  put_body(shaft_);
  v.insert(v.end(), friction_.begin(), friction_.end());
  v.insert(v.end(), outer_force_.begin(), outer_force_.end());
  v.insert(v.end(), inner_force_.begin(), inner_force_.end());
  v.insert(v.end(), cage_force_.begin(), cage_force_.end());
  for (double x : {dt_prev_, potential_, kinetic_, friction_work_, damping_work_, external_work_})
    v.push_back(x);
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
}

void HybridRollers::LoadState(const std::string& bytes) {
  const size_t z = rollers_.size();
  const size_t n = 6 * (z + 2) + kFrictionSlots * z + 3 * z + 6;
  if (bytes.size() != n * sizeof(double))
    throw InputError("hybrid_rollers: checkpoint state has the wrong size");
  std::vector<double> v(n);
  std::memcpy(v.data(), bytes.data(), bytes.size());
  size_t i = 0;
  auto get_body = [&](Body* b) {
    for (double* x : {&b->x, &b->y, &b->angle, &b->vx, &b->vy, &b->omega}) *x = v[i++];
  };
  for (Body& b : rollers_) get_body(&b);
  get_body(&cage_);
  get_body(&shaft_);
  for (double& x : friction_) x = v[i++];
  for (double& x : outer_force_) x = v[i++];
  for (double& x : inner_force_) x = v[i++];
  for (double& x : cage_force_) x = v[i++];
  for (double* x :
       {&dt_prev_, &potential_, &kinetic_, &friction_work_, &damping_work_, &external_work_})
    *x = v[i++];
}

}  // namespace spallkit::sim
