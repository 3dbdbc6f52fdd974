#include "sim/bearing/roller_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/checkpoint_io.h"
#include "core/constants.h"
#include "core/error.h"
#include "sim/bearing/rigid_outer_race.h"
#include "sim/quasistatic/harris_jones.h"
#include "sim/solver/stable_step.h"

namespace spallkit::sim {
namespace {

// Stick springs per roller: outer race, inner race, leading wall, trailing wall (the notched
// part of the roller), then outer and inner race of the intact part of a partial-length spall.
constexpr int kFrictionSlots = 6;
// Safety factor on the contacts' stable step (the solver scales only the element step).
constexpr double kContactSafety = 0.8;
// Rounding allowance of the "cannot touch" tests that skip a contact (m).
constexpr double kReachMargin = 1e-9;

// (cos, sin) of an angle advanced by da (the new angle is `angle`): a rotation by da with its
// Taylor series (exact to rounding for |da| <= 1e-2, a roller's spin over one step is ~1e-4)
// and the norm restored, else from the angle itself. Saves a sin and a cos per roller per step.
void RotateCosSin(double da, double angle, double* c, double* s) {
  if (!(std::abs(da) <= 1e-2)) {
    *c = std::cos(angle), *s = std::sin(angle);
    return;
  }
  const double a2 = da * da;
  const double cd = 1.0 - a2 * (0.5 - a2 * (1.0 / 24.0 - a2 * (1.0 / 720.0)));
  const double sd = da * (1.0 - a2 * (1.0 / 6.0 - a2 * (1.0 / 120.0 - a2 * (1.0 / 5040.0))));
  const double nc = *c * cd - *s * sd, ns = *s * cd + *c * sd;
  const double k = 1.5 - 0.5 * (nc * nc + ns * ns);  // one Newton step to the unit norm
  *c = nc * k, *s = ns * k;
}

}  // namespace

template <class F>
decltype(auto) RollerContacts::WithRace(F&& f) const {
  if (rigid_race_) return f(*rigid_race_);
  return f(*race_);
}

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

RollerContacts::RollerContacts(const Scene& scene,
                               const BearingMesh& housing,
                               double outer_race_mass,
                               const HybridOptions& options,
                               const CageGuideOptions& cage_guide)
    : scene_(scene), options_(options), cage_guide_(cage_guide), race_mass_(outer_race_mass) {
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
  inner_radius_ = housing.inner_raceway_radius_m;
  pocket_half_width_ = 0.5 * (g.bearing.element_diameter_m + g.pocket_clearance_m);
  pitch_radius_ = housing.pitch_radius_m;
  k_c_ = PalmgrenContactStiffness(t, options_.palmgren_coefficient);
  race_reach_ = kReachMargin;
  if (scene_.friction.model == contact::TractionModel::kEhl) {
    const double r = housing.roller_radius_m, eta = scene_.friction.ehl.inlet_viscosity_pa_s;
    const double r_o = housing.outer_raceway_radius_m, r_i = inner_radius_;
    film_per_speed_[0] = contact::MartinFilmCoefficient(eta, 1.0, r * r_o / (r_o - r), t);
    film_per_speed_[1] = contact::MartinFilmCoefficient(eta, 1.0, r * r_i / (r_i + r), t);
    // Entrainment stays below the inner race's surface speed in rolling (the roller's surface
    // and the race's move at (omega - omega_cage) r_i relative to the contact); capping A at
    // twice that bounds the reach.
    film_ceiling_ = 2.0 * std::abs(omega) * r_i * std::max(film_per_speed_[0], film_per_speed_[1]);
    race_reach_ = std::max(kReachMargin, contact::FilmReach(film_ceiling_, k_c_));
  }

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
    intact_profiles_.push_back(p);
    intact_profiles_.back().spalled = false;
    spall_fraction_.push_back(p.spalled ? f : 1.0);
    roller_mass_.push_back(rho_r * t * area);
    roller_inertia_.push_back(rho_r * t * polar);
    centroid_x_.push_back(cx);
    centroid_y_.push_back(cy);
    pocket_angle_.push_back(phi);
    pocket_cos_.push_back(std::cos(phi));
    pocket_sin_.push_back(std::sin(phi));
    intact_directions_.emplace_back(intact_profiles_.back());
    // Seated (model.start): touching the outer raceway along the pocket line, unless that lies
    // beyond the cage's radial play (a wide spall facing the race): the pocket holds it there.
    profiles_.push_back(p);
    directions_.emplace_back(p);
    const double centre_radius =
        scene_.model.start == StartPose::kSeated
            ? std::min(SeatOnOuterRace(j, phi, housing.outer_raceway_radius_m),
                       housing.pitch_radius_m + cage_guide_.radial_play_m)
            : housing.pitch_radius_m;
    Body b;
    b.x = centre_radius * std::cos(phi) + cx;
    b.y = centre_radius * std::sin(phi) + cy;
    rollers_.push_back(b);
  }
  if (scene_.model.start == StartPose::kSeated) shaft_.y = -SeatedShaftDrop();

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
        const double d = WrapAngle(rel - 2 * kPi / z * std::round(rel / (2 * kPi / z)));
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

  // Stable step of the contacts (the normal and the stick spring act together; stiffness at
  // twice the radial load, a bound on impacts): each contact is a two-body oscillator with
  // damping zeta of ITS critical value (reduced mass), so the central-difference limit is
  // 2/omega (sqrt(1 + zeta^2) - zeta) with
  //  - roller side: both races' springs on the roller's rim (effective mass m/3: translation
  //    plus rotation for a tangential force on a disc), omega^2 = 2 k (3/m_r);
  //  - ring side: omega^2 = k (3/m_r + 1/m_ring) for one contact on the ring's kernel nodes.
  {
    const double q = 2.0 * std::max(load, 1000.0);
    const double delta = PalmgrenApproach(q, k_c_);
    const double kn = 10.0 / 9.0 * q / delta;
    double m_min = roller_mass_[0];
    for (double m : roller_mass_) m_min = std::min(m_min, m);
    const double zeta = options_.contact_damping_ratio;
    bound_normal_stiffness_ = kn;
    const double k = kn * (1.0 + options_.tangential_stiffness_ratio);
    roller_dt_ = solver::DampedStableStep(std::sqrt(2.0 * k * 3.0 / m_min), zeta);
    ring_dt_ = solver::DampedStableStep(std::sqrt(k * (3.0 / m_min + 1.0 / race_mass_)), zeta);
    dt_limit_ = kContactSafety * std::min(roller_dt_, ring_dt_);
  }

  friction_.assign(kFrictionSlots * z, 0.0);
  anchor_depth_.assign(3 * kFrictionSlots * z, 0.0);
  anchor_power_.assign(3 * kFrictionSlots * z, 0.0);
  film_coefficient_.assign(3 * kFrictionSlots * z, 0.0);
  film_memory_.assign(3 * kFrictionSlots * z, {});
  outer_force_.assign(z, 0.0);
  inner_force_.assign(z, 0.0);
  cage_force_.assign(z, 0.0);
  // Inverse masses for the traction solve (SolveTraction): each roller's, and each counter
  // body's for a tangential force, in Counter order.
  for (int j = 0; j < z; ++j) {
    inverse_roller_mass_.push_back(1.0 / roller_mass_[j]);
    inverse_roller_inertia_.push_back(1.0 / roller_inertia_[j]);
  }
  inverse_counter_mass_[0] = 1.0 / race_mass_;
  inverse_counter_mass_[1] = 1.0 / shaft_mass_;
  inverse_counter_mass_[2] = 1.0 / cage_mass_;
  // Reduced masses of each roller with each counter body (normal; tangential with the roller's
  // m/3 for a force on its rim), in Counter order.
  for (int j = 0; j < z; ++j)
    for (double m_counter : {race_mass_, shaft_mass_, cage_mass_}) {
      reduced_mass_.push_back(1.0 / (1.0 / roller_mass_[j] + 1.0 / m_counter));
      reduced_mass_t_.push_back(1.0 / (3.0 / roller_mass_[j] + 1.0 / m_counter));
    }
  fx_.assign(z, 0.0);
  cos_.assign(z, 1.0);
  sin_.assign(z, 0.0);
  centre_x_.assign(z, 0.0);
  centre_y_.assign(z, 0.0);
  fy_.assign(z, 0.0);
  torque_.assign(z, 0.0);
  friction_law_.static_coefficient = scene_.friction.mu_static;
  friction_law_.dynamic_coefficient = scene_.friction.mu_dynamic;
  friction_law_.decay = scene_.friction.decay_s_m;
}

void RollerContacts::RollerCentre(int j, double* x, double* y) const {
  const Body& b = rollers_[j];
  const double c = std::cos(b.angle), s = std::sin(b.angle);
  *x = b.x - (c * centroid_x_[j] - s * centroid_y_[j]);
  *y = b.y - (s * centroid_x_[j] + c * centroid_y_[j]);
}

void RollerContacts::CircleCentre(int j, double* x, double* y) const {
  const Body& b = rollers_[j];
  *x = b.x - (cos_[j] * centroid_x_[j] - sin_[j] * centroid_y_[j]);
  *y = b.y - (sin_[j] * centroid_x_[j] + cos_[j] * centroid_y_[j]);
}

bool RollerContacts::SpallNearRace(int j, double margin, double min_relative_spin) const {
  if (!profiles_[j].spalled) return false;
  const Body& b = rollers_[j];
  // The spall turns past the race directions at the roller's spin relative to its orbit; a
  // roller that does not (trapped on its spall corners, resting) has no passage to resolve.
  const double r2 = b.x * b.x + b.y * b.y;
  const double orbit = r2 > 0.0 ? (b.x * b.vy - b.y * b.vx) / r2 : 0.0;
  if (std::abs(b.omega - orbit) < min_relative_spin) return false;
  if (!(widened_margin_ == margin)) {  // the cones' cosines, once per margin
    widened_margin_ = margin;
    widened_cos_.resize(profiles_.size());
    for (size_t k = 0; k < profiles_.size(); ++k)
      widened_cos_[k] = std::cos(std::min(kPi, profiles_[k].ContactHalfAngle() + margin));
  }
  const double cos_widened = widened_cos_[j];
  const double c = cos_[j], s = sin_[j];
  double x, y;
  CircleCentre(j, &x, &y);
  const double d_out = std::hypot(x, y);
  const double ex = shaft_.x - x, ey = shaft_.y - y, d_in = std::hypot(ex, ey);
  // Directions to the outer and the inner race in the roller's frame.
  const double out_x = x / d_out, out_y = y / d_out, in_x = ex / d_in, in_y = ey / d_in;
  return directions_[j].NearSpall(c * out_x + s * out_y, c * out_y - s * out_x, cos_widened) ||
         directions_[j].NearSpall(c * in_x + s * in_y, c * in_y - s * in_x, cos_widened);
}

int RollerContacts::ContactCircles(
    int j, double cx, double cy, double ux, double uy, double out[3][3]) const {
  // Body angle 0 (the start): body frame = world frame. The intact circle always counts when
  // the spall is shorter than the roller (its intact length reaches further than the rim edges).
  const RollerProfile& p = profiles_[j];
  const bool faces_spall = p.spalled && directions_[j].InSpall(ux, uy);
  int n = 0;
  if (!faces_spall || spall_fraction_[j] < 1.0)
    out[n][0] = cx, out[n][1] = cy, out[n++][2] = p.radius;
  if (faces_spall) {
    const double* kx = directions_[j].corner_x();
    const double* ky = directions_[j].corner_y();
    for (int k = 0; k < 2; ++k)
      out[n][0] = cx + kx[k], out[n][1] = cy + ky[k], out[n++][2] = p.edge_radius;
  }
  return n;
}

double RollerContacts::SeatOnOuterRace(int j, double phi, double outer_radius) const {
  // The circles that face the race (the intact circle, or the two rim fillets of a spall facing
  // it) against the raceway circle: the rim edges sit off the centre line, where the concave
  // race is closer, so the largest penetration is driven to zero by a few Newton-like steps.
  const double ux = std::cos(phi), uy = std::sin(phi);
  double rho = outer_radius - profiles_[j].Support(phi);
  for (int it = 0; it < 8; ++it) {
    double circles[3][3];
    const int n = ContactCircles(j, rho * ux, rho * uy, ux, uy, circles);
    double penetration = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < n; ++k)
      penetration = std::max(
          penetration, std::hypot(circles[k][0], circles[k][1]) + circles[k][2] - outer_radius);
    rho -= penetration;
  }
  return rho;
}

double RollerContacts::SeatedShaftDrop() const {
  // The load acts along -y. Lowering the shaft centre by s, a roller circle (centre q, radius a;
  // the intact circle or a rim fillet facing the bearing centre) touches the raceway when
  // |q - (0, -s)| = R_i + a: the smaller root s = -q_y - sqrt((R_i + a)^2 - q_x^2) for a circle
  // below the centre line.
  double drop = std::numeric_limits<double>::infinity();
  for (int j = 0; j < static_cast<int>(rollers_.size()); ++j) {
    double x, y;
    RollerCentre(j, &x, &y);
    const double d = std::hypot(x, y);
    double circles[3][3];
    const int n = ContactCircles(j, x, y, -x / d, -y / d, circles);
    for (int k = 0; k < n; ++k) {
      const double qx = circles[k][0], qy = circles[k][1], reach = inner_radius_ + circles[k][2];
      const double disc = reach * reach - qx * qx;
      if (!(qy < 0) || disc < 0) continue;
      const double s = -qy - std::sqrt(disc);
      if (s >= 0) drop = std::min(drop, s);
    }
  }
  return std::isfinite(drop) ? drop : 0.0;
}

int RollerContacts::RacePoints(int j,
                               int which,
                               const RollerProfile& p,
                               const ProfileDirections& dirs,
                               RacePoint out[3]) const {
  // Positions only; the outer race radius is filled in by the caller (needs the nodal state).
  const double cx = centre_x_[j], cy = centre_y_[j];
  double dx, dy;  // unit direction from the roller centre towards the race contact
  if (which == 0) {
    const double d = std::sqrt(cx * cx + cy * cy);
    dx = cx / d, dy = cy / d;
  } else {
    const double ex = shaft_.x - cx, ey = shaft_.y - cy, d = std::sqrt(ex * ex + ey * ey);
    dx = ex / d, dy = ey / d;
  }
  const double c = cos_[j], s = sin_[j];
  if (!p.spalled || !dirs.InSpall(c * dx + s * dy, c * dy - s * dx)) {
    out[0] = {cx + p.radius * dx, cy + p.radius * dy, -dx, -dy, 0.0};
    return 1;
  }
  // Rim edges: the fillet centres (the corners for sharp edges); the caller offsets them by
  // the fillet radius along the race normal through each.
  const double* kx = dirs.corner_x();
  const double* ky = dirs.corner_y();
  for (int k = 0; k < 2; ++k)
    out[k] = {cx + c * kx[k] - s * ky[k], cy + s * kx[k] + c * ky[k], -dx, -dy, 0.0};
  out[2] = {cx + p.radius * dx, cy + p.radius * dy, -dx, -dy, 0.0};
  return 2;
}

void RollerContacts::CounterVelocity(
    Counter body, double px, double py, double* vx, double* vy) const {
  if (body == Counter::kOuterRace) {
    WithRace([&](auto& race) { race.Velocity(px, py, vx, vy); });
  } else if (body == Counter::kShaft) {
    *vx = shaft_.vx - omega_s_ * (py - shaft_.y);
    *vy = shaft_.vy + omega_s_ * (px - shaft_.x);
  } else {
    *vx = cage_.vx - cage_.omega * (py - cage_.y);
    *vy = cage_.vy + cage_.omega * (px - cage_.x);
  }
}

void RollerContacts::ApplyCounter(Counter body, double px, double py, double fx, double fy) {
  if (body == Counter::kOuterRace) {
    WithRace([&](auto& race) { race.Apply(px, py, fx, fy); });
  } else if (body == Counter::kShaft) {
    shaft_fx_ += fx, shaft_fy_ += fy;
    shaft_torque_ += (px - shaft_.x) * fy - (py - shaft_.y) * fx;
  } else {
    cage_fx_ += fx, cage_fy_ += fy;
    cage_torque_ += (px - cage_.x) * fy - (py - cage_.y) * fx;
  }
}

double RollerContacts::PalmgrenPower(double d, int anchor) {
  return PalmgrenPowerNear(d, &anchor_depth_[anchor], &anchor_power_[anchor]);
}

double RollerContacts::Contact(
    int j, Counter body, bool palmgren, RacePoint* pts, int npts, double* spring, double scale) {
  const double zeta = options_.contact_damping_ratio;
  const double dt = dt_;
  // Friction and damping work: f^n . (v^(n-1/2) + v^(n+1/2)) / 2 dt_avg, the work the central
  // differences give these forces (with v^(n-1/2) alone it is first order in the step).
  const double half = 0.5 * (0.5 * (dt_prev_ + dt));
  const Body& b = rollers_[j];
  auto Defer = [&](const RacePoint& p, double fx, double fy, int friction) {
    DeferDissipation(j, body, p.px, p.py, fx, fy, friction);
  };
  // Damping of each contact: a fraction of ITS critical value, i.e. with the reduced mass of
  // the roller and the counter body (LS-DYNA's viscous contact damping does the same with the
  // slave and master nodal masses); for the outer race, its effective contact mass.
  const int counter = static_cast<int>(body);
  const double m = reduced_mass_[3 * j + counter];
  const double m_t = reduced_mass_t_[3 * j + counter];
  // Elastic load and stiffness of each point. A rim pair with the intact circle's point
  // (npts == 3) is one contact whose two edge zones overlap by what the circle would carry
  // (RaceContacts): V = V(d_1) + V(d_2) - V(d_s), d_s = d_1 + d_2 - d_c the shared zone's
  // depth, whose forces are Q(d_k) - Q(d_s) at the edges and Q(d_s) at the circle's point.
  double qe_pt[3] = {0, 0, 0}, kn_pt[3] = {0, 0, 0};
  // The conservative part of each point's elastic load (the rest is the lubricant film's, whose
  // work is booked with the damping; without a film, all of it).
  double qc_pt[3] = {0, 0, 0};
  double tx = -pts[0].ny, ty = pts[0].nx;
  // Each point's relative velocity (roller minus counter body) and entrainment speed, from the
  // velocity of the roller's circle centre (the contact points move with it).
  const double centre_vx = b.vx - b.omega * (centre_y_[j] - b.y);
  const double centre_vy = b.vy + b.omega * (centre_x_[j] - b.x);
  double rvx[3], rvy[3], ue[3];  // ue: twice the entrainment speed
  auto point_velocity = [&](int k) {
    const RacePoint& p = pts[k];
    double vx, vy;
    CounterVelocity(body, p.px, p.py, &vx, &vy);
    rvx[k] = b.vx - b.omega * (p.py - b.y) - vx;
    rvy[k] = b.vy + b.omega * (p.px - b.x) - vy;
    const double u_roller = b.omega * ((p.px - centre_x_[j]) * ty - (p.py - centre_y_[j]) * tx);
    const double u_counter = (vx - centre_vx) * tx + (vy - centre_vy) * ty;
    ue[k] = u_roller + u_counter;
  };
  // The lubricant film's coefficient A of point k (contact/film_lift.h), 0 without a film. The
  // film needs every point's entrainment before its load; without one a point's velocity is read
  // only where it carries load (the outer race's velocity is a kernel sum in the hybrid).
  const double film_per_speed = palmgren && counter < 2 ? film_per_speed_[counter] : 0.0;
  if (film_per_speed > 0)
    for (int k = 0; k < npts; ++k) point_velocity(k);
  auto film = [&](int k) {
    if (!(film_per_speed > 0)) return 0.0;
    return std::min(film_ceiling_, film_per_speed * std::abs(0.5 * ue[k])) * scale;
  };
  // Palmgren's law at penetration d > 0 (load, stiffness dQ/dd and potential 9/19 Q d), or with
  // the film at any d (point's A > 0).
  const int anchor = 3 * static_cast<int>(spring - friction_.data());
  auto race_law =
      [&](double d, int point, double a, double* load, double* stiffness, double* conservative) {
        double& a_last = film_coefficient_[anchor + point];
        if (a > 0 || a_last > 0) {
          const contact::FilmContactLoad f =
              contact::FilmLineContact(d, a, scale * k_c_, &film_memory_[anchor + point]);
          *load = f.load, *stiffness = f.stiffness, *conservative = f.conservative_load;
          // The elastic energy that the change of A since the last step moved without work (first
          // order in the change; the shared zone's potential is subtracted): the film's, booked
          // with the damping so that the balance keeps only the integration's error.
          damping_work_ -= (point == 2 ? -1.0 : 1.0) * f.potential_per_film * (a - a_last);
          a_last = a;
          return f.potential;
        }
        if (!(d > 0)) return *load = *stiffness = *conservative = 0.0;
        *load = *conservative = scale * k_c_ * PalmgrenPower(d, anchor + point);
        *stiffness = 10.0 / 9.0 * *load / d;
        return *load * d * (9.0 / 19.0);
      };
  for (int k = 0; k < std::min(npts, 2); ++k) {
    const double d = pts[k].delta;
    if (palmgren) {
      step_potential_ += race_law(d, k, film(k), &qe_pt[k], &kn_pt[k], &qc_pt[k]);
    } else if (d > 0) {
      kn_pt[k] = options_.cage_stiffness_n_per_m;
      qe_pt[k] = qc_pt[k] = kn_pt[k] * d;
      step_potential_ += 0.5 * qe_pt[k] * d;
    }
  }
  if (npts == 3) {
    const double shared = pts[0].delta + pts[1].delta - pts[2].delta;
    const double a = film(2);
    if (palmgren && (shared > 0 || a > 0)) {
      double qs, ks, cs;
      step_potential_ -= race_law(shared, 2, a, &qs, &ks, &cs);
      for (int k = 0; k < 2; ++k) {
        qe_pt[k] = std::max(0.0, qe_pt[k] - qs);
        kn_pt[k] = std::max(0.0, kn_pt[k] - ks);
        qc_pt[k] = std::max(0.0, qc_pt[k] - cs);
      }
      qe_pt[2] = qs, kn_pt[2] = ks, qc_pt[2] = cs;
    }
  }
  double q[3] = {0, 0, 0}, q_total = 0, kn_total = 0, vt_acc = 0, ue_acc = 0;
  for (int k = 0; k < npts; ++k) {
    const RacePoint& p = pts[k];
    if (!(qe_pt[k] > 0)) continue;
    if (!(film_per_speed > 0)) point_velocity(k);
    const double qe = qe_pt[k], kn = kn_pt[k];
    const double rate = -(rvx[k] * p.nx + rvy[k] * p.ny);  // d delta / dt
    const double c = 2.0 * zeta * std::sqrt(kn * m);
    q[k] = std::max(0.0, qe + c * rate);
    // Damping and film work, first half (v^(n-1/2)); the second half in FinishDissipation.
    const double dissipative = q[k] - qc_pt[k];
    damping_work_ += dissipative * rate * half;
    Defer(p, dissipative * p.nx, dissipative * p.ny, 0);
    q_total += q[k];
    kn_total += kn;
    vt_acc += q[k] * (rvx[k] * tx + rvy[k] * ty);
    ue_acc += q[k] * 0.5 * ue[k];
  }
  if (!(q_total > 0)) {
    *spring = 0.0;
    return 0.0;
  }
  const double vt = vt_acc / q_total;
  double f = 0.0;
  if (palmgren && scene_.friction.model == contact::TractionModel::kEhl) {
    // Lubricated race contact: the traction curve of the slide-to-roll ratio, no stick; solved
    // with the roller's other lubricated contacts once all its other forces are known.
    TractionContact& c = traction_[num_traction_++];
    c.body = body, c.tx = tx, c.ty = ty, c.normal = q_total, c.slip = vt;
    c.entrainment = ue_acc / q_total, c.spring = spring, c.npts = 0, c.arm = 0.0;
    for (int k = 0; k < npts; ++k) {
      if (!(q[k] > 0)) continue;
      const double w = q[k] / q_total;
      c.px[c.npts] = pts[k].px, c.py[c.npts] = pts[k].py, c.w[c.npts++] = w;
      c.arm += w * ((pts[k].px - b.x) * ty - (pts[k].py - b.y) * tx);
    }
  } else {
    // The contact module's friction law: stick spring returned to mu(v_t) Q, plus a damper on
    // the stick spring (capped too).
    const double cap = friction_law_.Coefficient(vt) * q_total;
    const double kt = options_.tangential_stiffness_ratio * kn_total;
    const double ct = 2.0 * zeta * std::sqrt(kt * m_t);
    const double fs = contact::ReturnMap(*spring, vt * dt, kt, cap).force;
    f = std::clamp(fs - ct * vt, -cap, cap);
    *spring = fs;
    friction_work_ -= f * vt * half;
  }
  for (int k = 0; k < npts; ++k) {
    if (!(q[k] > 0)) continue;
    const RacePoint& p = pts[k];
    const double ft = f * q[k] / q_total;
    if (ft != 0.0) Defer(p, ft * tx, ft * ty, 1);
    const double fx = q[k] * p.nx + ft * tx, fy = q[k] * p.ny + ft * ty;
    fx_[j] += fx, fy_[j] += fy;
    torque_[j] += (p.px - b.x) * fy - (p.py - b.y) * fx;
    ApplyCounter(body, p.px, p.py, -fx, -fy);
  }
  return q_total;
}

void RollerContacts::DeferDissipation(
    int j, Counter body, double px, double py, double fx, double fy, int friction) {
  if (!options_.energy_books) return;
  const Body& b = rollers_[j];
  DissipativeForce d;
  d.fx = fx, d.fy = fy;
  d.ax = px - b.x, d.ay = py - b.y;
  d.px = px, d.py = py;
  const Body& c = body == Counter::kShaft ? shaft_ : cage_;
  d.bx = px - c.x, d.by = py - c.y;
  d.omega = body == Counter::kShaft ? omega_s_ : 0.0;
  d.weight = 0.5 * (0.5 * (dt_prev_ + dt_));
  d.roller = j, d.counter = static_cast<int>(body), d.friction = friction;
  pending_.push_back(d);
}

void RollerContacts::SolveTraction(int j) {
  const int n = num_traction_;
  if (n == 0) return;
  num_traction_ = 0;
  const Body& b = rollers_[j];
  const double dt_avg = 0.5 * (dt_prev_ + dt_), half = 0.5 * dt_avg;
  const double dt_m = dt_avg * inverse_roller_mass_[j], dt_i = dt_avg * inverse_roller_inertia_[j];
  // The roller's velocity change over the step from its forces so far (normal, damping, cage):
  // the free slip of each contact. The counter bodies' changes are left to the next step (the
  // ring and the shaft are much heavier, the shaft's spin is prescribed).
  const double dvx = dt_m * fx_[j], dvy = dt_m * fy_[j], dw = dt_i * torque_[j];
  // The solve's arrays: scratch members, of which the first n (n x n) entries are written here
  // (zero-filled locals were a measurable part of the step).
  double* normal = solve_.normal;
  double* free_slip = solve_.free_slip;
  double* entrainment = solve_.entrainment;
  double* compliance = solve_.compliance;
  double* force = solve_.force;
  double* secant = solve_.secant;
  for (int k = 0; k < n; ++k) {
    const TractionContact& c = traction_[k];
    normal[k] = c.normal, entrainment[k] = c.entrainment;
    free_slip[k] = c.slip + c.tx * dvx + c.ty * dvy + c.arm * dw;
    for (int l = 0; l < n; ++l) {
      const TractionContact& e = traction_[l];
      compliance[k * n + l] = (c.tx * e.tx + c.ty * e.ty) * dt_m + c.arm * e.arm * dt_i;
    }
    compliance[k * n + k] += dt_avg * inverse_counter_mass_[static_cast<int>(c.body)];
  }
  for (int k = 0; k < n; ++k) secant[k] = *traction_[k].spring;
  contact::SolveImplicitTraction(
      scene_.friction.ehl, n, normal, free_slip, entrainment, compliance, secant, force);
  for (int k = 0; k < n; ++k) {
    const TractionContact& c = traction_[k];
    const double f = force[k];
    *c.spring = secant[k];
    friction_work_ -= f * c.slip * half;
    for (int i = 0; i < c.npts; ++i) {
      const double fx = f * c.w[i] * c.tx, fy = f * c.w[i] * c.ty;
      DeferDissipation(j, c.body, c.px[i], c.py[i], fx, fy, 1);
      fx_[j] += fx, fy_[j] += fy;
      torque_[j] += (c.px[i] - b.x) * fy - (c.py[i] - b.y) * fx;
      ApplyCounter(c.body, c.px[i], c.py[i], -fx, -fy);
    }
  }
}

void RollerContacts::RaceContacts(
    int j, const RollerProfile& prof, const ProfileDirections& dirs, double scale, int slot) {
  RacePoint pts[3];
  // Outer race. A profile point is a circle of radius rad around a centre q (the roller's
  // circle, or a rim fillet: its centre and radius, a corner with radius 0); the race gives its
  // gap and the normal of the deformed race.
  // Every profile point lies inside the roller's circle: a race the circle does not reach
  // (by more than rounding) has no contact, and its stick spring is released as in Contact.
  const double rho = prof.edge_radius;
  const double cx = centre_x_[j], cy = centre_y_[j];
  if (WithRace([&](auto& race) { return race.MayTouch(cx, cy, prof.radius + race_reach_); })) {
    int n = RacePoints(j, 0, prof, dirs, pts);
    double qx[2], qy[2], rad[2];
    if (n == 1) {
      qx[0] = cx, qy[0] = cy;
      rad[0] = prof.radius;
    } else {
      for (int k = 0; k < 2; ++k) qx[k] = pts[k].px, qy[k] = pts[k].py, rad[k] = rho;
    }
    WithRace([&](auto& race) {
      for (int k = 0; k < n; ++k) race.Gap(qx[k], qy[k], rad[k], &pts[k]);
    });
    if (n == 2) {  // the intact circle's point: what the rim pair's zones share
      WithRace([&](auto& race) { race.Gap(cx, cy, prof.radius, &pts[2]); });
      n = 3;
    }
    outer_force_[j] += Contact(j, Counter::kOuterRace, true, pts, n, &friction_[slot], scale);
  } else {
    friction_[slot] = 0.0;
  }
  // Inner race (rigid ring on the shaft).
  const double sx = shaft_.x - cx, sy = shaft_.y - cy;
  if (inner_radius_ - std::sqrt(sx * sx + sy * sy) + prof.radius < -race_reach_) {
    friction_[slot + 1] = 0.0;
    return;
  }
  int n = RacePoints(j, 1, prof, dirs, pts);
  for (int k = 0; k < n; ++k) {
    const double ex = pts[k].px - shaft_.x, ey = pts[k].py - shaft_.y;
    const double d = std::sqrt(ex * ex + ey * ey);
    if (n == 2) {  // rim edge: normal through the fillet centre, surface point rho closer
      pts[k].nx = ex / d, pts[k].ny = ey / d;
      pts[k].px -= rho * pts[k].nx, pts[k].py -= rho * pts[k].ny;
      pts[k].delta = inner_radius_ - (d - rho);
    } else {
      pts[k].delta = inner_radius_ - d;
    }
  }
  if (n == 2) {  // the intact circle's point, as for the outer race
    const double ex = pts[2].px - shaft_.x, ey = pts[2].py - shaft_.y;
    pts[2].delta = inner_radius_ - std::sqrt(ex * ex + ey * ey);
    n = 3;
  }
  inner_force_[j] += Contact(j, Counter::kShaft, true, pts, n, &friction_[slot + 1], scale);
}

void RollerContacts::CageContacts(int j) {
  const double f = spall_fraction_[j];
  // Cage pocket walls: straight lines +-W/2 from the pocket's centre line.
  const double cx = centre_x_[j], cy = centre_y_[j];
  // Pocket centre line (cos, sin of pocket angle + cage angle).
  const double ex = pocket_cos_[j] * cage_cos_ - pocket_sin_[j] * cage_sin_;
  const double ey = pocket_sin_[j] * cage_cos_ + pocket_cos_[j] * cage_sin_;
  const double twx = -ey, twy = ex;
  const double lateral = (cx - cage_.x) * twx + (cy - cage_.y) * twy;
  // The force acts at the profile's extreme point towards the wall (a rim edge when the spall
  // faces it), so that its torque matches the gap's dependence on the roller's angle. The
  // intact part of a partial-length spall reaches further than the notched part. Every profile
  // point is inside the circle: a wall the circle does not reach has no contact.
  const RollerProfile& wall_prof = f < 1.0 ? intact_profiles_[j] : profiles_[j];
  const ProfileDirections& wall_dirs = f < 1.0 ? intact_directions_[j] : directions_[j];
  const double reach = wall_prof.radius - pocket_half_width_ + kReachMargin;
  const double rc = cos_[j], rs = sin_[j];
  // Direction of the leading wall's normal (tw) in the roller's frame.
  const double ux = rc * twx + rs * twy, uy = rc * twy - rs * twx;
  double* lead_spring = &friction_[kFrictionSlots * j + 2];
  double* trail_spring = &friction_[kFrictionSlots * j + 3];
  double q_lead = 0.0, q_trail = 0.0;
  if (lateral + reach > 0) {
    double lx, ly;
    const double h_lead = wall_dirs.SupportPoint(ux, uy, &lx, &ly);
    RacePoint lead{cx + rc * lx - rs * ly,
                   cy + rs * lx + rc * ly,
                   -twx,
                   -twy,
                   lateral + h_lead - pocket_half_width_};
    q_lead = Contact(j, Counter::kCage, false, &lead, 1, lead_spring);
  } else {
    *lead_spring = 0.0;
  }
  if (-lateral + reach > 0) {
    double kx, ky;
    const double h_trail = wall_dirs.SupportPoint(-ux, -uy, &kx, &ky);
    RacePoint trail{cx + rc * kx - rs * ky,
                    cy + rs * kx + rc * ky,
                    twx,
                    twy,
                    -lateral + h_trail - pocket_half_width_};
    q_trail = Contact(j, Counter::kCage, false, &trail, 1, trail_spring);
  } else {
    *trail_spring = 0.0;
  }
  cage_force_[j] = q_lead + q_trail;
  // Radial retention (roller-guided cage): the pocket keeps the roller within +-radial_play of
  // the pitch radius of the cage frame, else the cage could drift sideways with the rollers
  // sliding along their orbits (walls alone allow that mode).
  const double radial = (cx - cage_.x) * ex + (cy - cage_.y) * ey - pitch_radius_;
  const double q_signed = cage_guide_.RadialForce(radial, &step_potential_);  // along e
  if (q_signed != 0.0) {
    const double q = std::abs(q_signed);
    const double fx = q_signed * ex, fy = q_signed * ey;
    fx_[j] += fx, fy_[j] += fy;
    torque_[j] += (cx - rollers_[j].x) * fy - (cy - rollers_[j].y) * fx;
    ApplyCounter(Counter::kCage, cx, cy, -fx, -fy);
    cage_force_[j] += q;
  }
}

void RollerContacts::FinishDissipation() {
  for (const DissipativeForce& d : pending_) {
    const Body& b = rollers_[d.roller];
    const double vrx = b.vx - b.omega * d.ay, vry = b.vy + b.omega * d.ax;
    double vcx, vcy;
    if (d.counter == static_cast<int>(Counter::kOuterRace)) {
      WithRace([&](auto& race) { race.Velocity(d.px, d.py, &vcx, &vcy); });
    } else {
      const Body& c = d.counter == static_cast<int>(Counter::kShaft) ? shaft_ : cage_;
      const double w = d.counter == static_cast<int>(Counter::kShaft) ? d.omega : c.omega;
      vcx = c.vx - w * d.by, vcy = c.vy + w * d.bx;
    }
    const double work = -(d.fx * (vrx - vcx) + d.fy * (vry - vcy)) * d.weight;
    (d.friction ? friction_work_ : damping_work_) += work;
  }
  pending_.clear();
}

void RollerContacts::Step(OuterRace& race, double t, double dt) {
  race_ = &race;
  rigid_race_ = race.AsRigid();
  FinishDissipation();
  dt_ = dt;
  omega_s_ = speed_(t);
  shaft_fx_ = shaft_fy_ = shaft_torque_ = cage_fx_ = cage_fy_ = cage_torque_ = 0.0;
  step_potential_ = 0.0;
  std::fill(fx_.begin(), fx_.end(), 0.0);
  std::fill(fy_.begin(), fy_.end(), 0.0);
  std::fill(torque_.begin(), torque_.end(), 0.0);
  cage_cos_ = std::cos(cage_.angle), cage_sin_ = std::sin(cage_.angle);
  for (int j = 0; j < num_rollers(); ++j) CircleCentre(j, &centre_x_[j], &centre_y_[j]);
  for (int j = 0; j < num_rollers(); ++j) {
    const double f = spall_fraction_[j];
    outer_force_[j] = inner_force_[j] = 0.0;
    RaceContacts(j, profiles_[j], directions_[j], f, kFrictionSlots * j);
    if (f < 1.0)
      RaceContacts(j, intact_profiles_[j], intact_directions_[j], 1.0 - f, kFrictionSlots * j + 4);
    CageContacts(j);
    SolveTraction(j);
  }
  potential_ = step_potential_;
  Integrate(t, dt);
  race_ = nullptr;
  rigid_race_ = nullptr;
}

void RollerContacts::Integrate(double t, double dt) {
  const double dt_avg = 0.5 * (dt_prev_ + dt);
  double kinetic = 0.0, centred = 0.0;
  // 1/2 m v^(n-1/2) . v^(n+1/2): the kinetic energy at t^n that central differences conserve
  // exactly with linear springs (no first-order oscillation in the step).
  auto centred_energy = [](const Body& a, const Body& b, double m, double inertia) {
    return 0.5 * m * (a.vx * b.vx + a.vy * b.vy) + 0.5 * inertia * a.omega * b.omega;
  };
  const bool books = options_.energy_books;
  for (int j = 0; j < num_rollers(); ++j) {
    Body& b = rollers_[j];
    const Body old = b;
    b.Advance(fx_[j], fy_[j], torque_[j], roller_mass_[j], roller_inertia_[j], dt_avg, dt);
    RotateCosSin(dt * b.omega, b.angle, &cos_[j], &sin_[j]);
    if (!books) continue;
    kinetic += b.KineticEnergy(roller_mass_[j], roller_inertia_[j]);
    centred += centred_energy(old, b, roller_mass_[j], roller_inertia_[j]);
  }
  const Body cage_old = cage_;
  cage_.Advance(cage_fx_, cage_fy_, cage_torque_, cage_mass_, cage_inertia_, dt_avg, dt);
  kinetic += cage_.KineticEnergy(cage_mass_, cage_inertia_);
  centred += centred_energy(cage_old, cage_, cage_mass_, cage_inertia_);
  const double load = load_(t);
  const Body shaft_old = shaft_;
  const double vy_old = shaft_.vy;
  shaft_.Translate(shaft_fx_, shaft_fy_ + load, shaft_mass_, dt_avg, dt);
  shaft_.angle = angle_(t + dt);
  shaft_.omega = speed_(t + 0.5 * dt);
  kinetic += shaft_.TranslationalEnergy(shaft_mass_);
  centred += centred_energy(shaft_old, shaft_, shaft_mass_, 0.0);
  kinetic_ = kinetic;
  centred_kinetic_ = centred;
  // Load work over the half steps around t^n; drive torque = -(contact torque on the shaft),
  // at the spin the contacts' relative velocities use in both halves. The second halves are
  // booked now and left out of ExternalWork() until the next step.
  const double load_half = 0.5 * dt_avg * load * shaft_.vy;
  const double drive_half = -0.5 * dt_avg * shaft_torque_ * omega_s_;
  external_work_ += 0.5 * dt_avg * load * vy_old + load_half + 2.0 * drive_half;
  external_half_ = load_half + drive_half;
  dt_prev_ = dt;
}

std::string RollerContacts::SaveState() const {
  CheckpointWriter out;
  auto put_body = [&](const Body& b) {
    for (double x : {b.x, b.y, b.angle, b.vx, b.vy, b.omega}) out.Put(x);
  };
  for (const Body& b : rollers_) put_body(b);
  put_body(cage_);
  put_body(shaft_);
  for (const std::vector<double>* v : StateVectors(*this))
    for (double x : *v) out.Put(x);
  for (double x : {dt_prev_,
                   potential_,
                   kinetic_,
                   friction_work_,
                   damping_work_,
                   external_work_,
                   external_half_,
                   centred_kinetic_})
    out.Put(x);
  out.PutVector(pending_);
  out.PutVector(film_memory_);
  return out.Take();
}

void RollerContacts::LoadState(const std::string& bytes) {
  const size_t z = rollers_.size();
  const size_t n = 6 * (z + 2) + 10 * kFrictionSlots * z + 5 * z + 8;
  if (bytes.size() < n * sizeof(double))
    throw InputError("roller contacts: checkpoint state has the wrong size");
  CheckpointReader in(bytes, "roller contacts: checkpoint state");
  auto get_body = [&](Body* b) {
    for (double* x : {&b->x, &b->y, &b->angle, &b->vx, &b->vy, &b->omega}) *x = in.Get<double>();
  };
  for (Body& b : rollers_) get_body(&b);
  get_body(&cage_);
  get_body(&shaft_);
  for (std::vector<double>* v : StateVectors(*this))
    for (double& x : *v) x = in.Get<double>();
  for (double* x : {&dt_prev_,
                    &potential_,
                    &kinetic_,
                    &friction_work_,
                    &damping_work_,
                    &external_work_,
                    &external_half_,
                    &centred_kinetic_})
    *x = in.Get<double>();
  pending_ = in.GetVector<DissipativeForce>();
  for (const DissipativeForce& d : pending_)
    if (d.roller < 0 || d.roller >= static_cast<int>(z) || d.counter < 0 || d.counter > 2)
      throw InputError("roller contacts: checkpoint state has a bad pending contact force");
  in.GetVectorInto(&film_memory_, "roller contacts: film law memory");
  if (!in.AtEnd()) throw InputError("roller contacts: checkpoint state has the wrong size");
}

}  // namespace spallkit::sim
