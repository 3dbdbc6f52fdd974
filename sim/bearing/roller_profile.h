// Exact cross-section of a rigid roller with a rectangular spall: the geometry the hybrid and
// lumped bearing models put in contact with the races (docs/BEARING_MODEL.md, "The hybrid model").
#pragma once

namespace spallkit::sim {

// Angle wrapped to (-pi, pi].
double WrapAngle(double a);

// Exact section of a roller: circle of radius r, optionally with a flat-bottomed rectangular
// spall (chord width w at the surface, parallel walls, bottom at depth h below the intact
// surface) centred on body-frame direction `angle`. The two rim edges (wall meets circle) are
// sharp (edge_radius = 0) or rounded by a fillet of radius rho tangent to the wall and the
// circle; a race then touches a rim edge on its fillet circle.
struct RollerProfile {
  double radius = 0.0;
  bool spalled = false;
  double width = 0.0, depth = 0.0, angle = 0.0, edge_radius = 0.0;

  // Half the angle the spall cuts out of the circle: asin(w / 2r).
  double HalfAngle() const;
  // Half-angle of the directions in which the spall's hull (the rim edges) rather than the
  // circle is the extreme of the profile: the direction of a fillet centre, atan2(a + rho, v_f);
  // = HalfAngle() for sharp edges.
  double ContactHalfAngle() const;
  // True when body-frame direction a (rad) points into the spall (|a - angle| < ContactHalfAngle).
  bool InSpall(double a) const;
  // The centres of the two rim fillets (body frame, relative to the circle centre); the rim
  // corners themselves for sharp edges. A rim edge is the circle of radius edge_radius there.
  void RimCorners(double cx[2], double cy[2]) const;
  // Support function: max over the profile of p . (cos a, sin a), p from the circle centre.
  double Support(double a) const;
  // The same, and the extreme point itself (body frame, from the circle centre) in *px, *py:
  // a rim edge's surface point when a points into the spall, else radius * (cos a, sin a).
  double SupportPoint(double a, double* px, double* py) const;
  // Section properties: area (m^2), centroid (m, from the circle centre) and polar second
  // moment about the centroid (m^4). Exact up to a 1e-7 quadrature of the spall region.
  struct Properties {
    double area = 0.0, cx = 0.0, cy = 0.0, polar = 0.0;
  };
  Properties SectionProperties() const;
};

// The same queries for directions given as unit vectors (body frame), with the profile's trig
// done once: the per-step form the rigid-roller contacts use (no atan2, sin or cos per query).
class ProfileDirections {
 public:
  ProfileDirections() = default;
  explicit ProfileDirections(const RollerProfile& profile);
  // RollerProfile::InSpall for the direction (ux, uy).
  bool InSpall(double ux, double uy) const {
    return spalled_ && ux * axis_x_ + uy * axis_y_ > cos_half_;
  }
  // Whether the direction (ux, uy) is within the spall's contact cone widened to the cosine
  // `cos_widened` of its half-angle (see RollerContacts::SpallNearRace).
  bool NearSpall(double ux, double uy, double cos_widened) const {
    return spalled_ && ux * axis_x_ + uy * axis_y_ > cos_widened;
  }
  // RollerProfile::SupportPoint for the direction (ux, uy).
  double SupportPoint(double ux, double uy, double* px, double* py) const;
  // RollerProfile::RimCorners.
  const double* corner_x() const { return corner_x_; }
  const double* corner_y() const { return corner_y_; }

 private:
  bool spalled_ = false;
  double radius_ = 0, edge_radius_ = 0, axis_x_ = 1, axis_y_ = 0, cos_half_ = 1;
  double corner_x_[2] = {0, 0}, corner_y_[2] = {0, 0};
};

}  // namespace spallkit::sim
