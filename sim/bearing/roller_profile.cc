#include "sim/bearing/roller_profile.h"

#include <algorithm>
#include <cmath>

#include "core/constants.h"

namespace spallkit::sim {

double WrapAngle(double a) { return std::remainder(a, 2.0 * kPi); }

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
  return spalled && std::abs(WrapAngle(a - angle)) < ContactHalfAngle();
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

ProfileDirections::ProfileDirections(const RollerProfile& p)
    : spalled_(p.spalled), radius_(p.radius), edge_radius_(p.edge_radius) {
  if (!spalled_) return;
  axis_x_ = std::cos(p.angle), axis_y_ = std::sin(p.angle);
  cos_half_ = std::cos(p.ContactHalfAngle());
  p.RimCorners(corner_x_, corner_y_);
}

double ProfileDirections::SupportPoint(double ux, double uy, double* px, double* py) const {
  double x = radius_ * ux, y = radius_ * uy;
  if (InSpall(ux, uy)) {
    const int k =
        corner_x_[0] * ux + corner_y_[0] * uy >= corner_x_[1] * ux + corner_y_[1] * uy ? 0 : 1;
    x = corner_x_[k] + edge_radius_ * ux, y = corner_y_[k] + edge_radius_ * uy;
  }
  *px = x, *py = y;
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

}  // namespace spallkit::sim
