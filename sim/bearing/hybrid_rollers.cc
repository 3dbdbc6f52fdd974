#include "sim/bearing/hybrid_rollers.h"

#include <cmath>

#include "core/error.h"

namespace spallkit::sim {

void FeOuterRace::Gap(double qx, double qy, double rad, RacePoint* p) const {
  // delta = |q| + rad - R(theta_q). The force on the roller is -Q grad_q delta, i.e. along the
  // normal of the DEFORMED raceway, e_q - (R'/|q|) t_q: with the radial normal alone a roller
  // moving along a sloped (loaded) raceway would change delta without work (energy leak).
  const double d = std::hypot(qx, qy);
  const double ex = qx / d, ey = qy / d;
  double slope;
  const double race = kernel_.Radius(*state_, std::atan2(qy, qx), &slope);
  const double gx = ex + slope / d * ey, gy = ey - slope / d * ex;  // e - (R'/d) t
  const double g = std::hypot(gx, gy);
  p->nx = -gx / g, p->ny = -gy / g;
  p->px = qx - rad * p->nx, p->py = qy - rad * p->ny;
  p->delta = d + rad - race;
}

void FeOuterRace::Velocity(double px, double py, double* vx, double* vy) const {
  kernel_.Velocity(*state_, std::atan2(py, px), vx, vy);
}

void FeOuterRace::Apply(double px, double py, double fx, double fy) {
  kernel_.Spread(*state_, std::atan2(py, px), fx, fy);
}

HybridRollers::HybridRollers(const Scene& scene,
                             const BearingMesh& housing,
                             const fe::NodalState& state,
                             const HybridOptions& options,
                             const CageGuideOptions& cage_guide)
    : kernel_(housing.mesh,
              "outer_ring.raceway",
              housing.outer_raceway_radius_m,
              options.spread_half_width_m),
      race_(kernel_) {
  std::string err;
  if (!options.IsValid(&err)) throw InputError(err);
  rollers_ = std::make_unique<RollerContacts>(
      scene, housing, kernel_.ContactMass(state), options, cage_guide);
}

void HybridRollers::AddForces(fe::NodalState& state, double t, double dt) {
  race_.Bind(&state);
  rollers_->Step(race_, t, dt);
  race_.Bind(nullptr);
}

}  // namespace spallkit::sim
