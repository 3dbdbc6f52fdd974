#include "sim/contact/contact_law.h"

namespace spallkit::sim::contact {

void ContactLaw::Apply(
    double k, const ContactKinematics& p, double dt, StickSpring spring, ContactSlot* slot) const {
  const double nx = p.nx, ny = p.ny, penetration = p.penetration;
  const double tx = -ny, ty = nx;
  const double vn = p.rvx * nx + p.rvy * ny, vt = p.rvx * tx + p.rvy * ty;
  const double fn_elastic = k * penetration;
  double fn = fn_elastic;
  const double zeta = options_.normal_damping_ratio;
  if (zeta > 0.0) {
    const double reduced = p.inverse_mass_sum > 0.0 ? 1.0 / p.inverse_mass_sum : 0.0;
    const double c = 2.0 * zeta * std::sqrt(k * reduced);
    fn = std::max(0.0, fn_elastic - c * vn);
    slot->damping_work = -(fn - fn_elastic) * vn * dt;
  }
  slot->stored = 0.5 * k * penetration * penetration;
  double ft = 0.0;
  if (!options_.friction.IsFrictionless()) {
    const double kt = options_.tangential_stiffness_ratio * k;
    const double mu = options_.friction.Coefficient(vt);
    const FrictionUpdate update = ReturnMap(*spring.force, vt * dt, kt, mu * fn);
    ft = update.force;
    slot->friction_work = update.dissipation;
    slot->stored += 0.5 * ft * ft / kt;
    *spring.force = ft;
    *spring.stiffness = kt;
  }
  slot->fn = fn;
  slot->penetration = penetration;
  slot->fnx = fn * nx;
  slot->fny = fn * ny;
  slot->ftx = ft * tx;
  slot->fty = ft * ty;
}

}  // namespace spallkit::sim::contact
