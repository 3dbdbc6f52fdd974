// The force law at one contact point (a slave node, the arcs' blended point or the spline point),
// shared by every contact strategy of a ContactPair:
//   normal:     F_n = k * penetration + damping, damping = ratio * 2 sqrt(k m*) * (-v_n), F_n >= 0
//   tangential: a stick spring F_t <- F_t - k_t v_t dt, capped at mu(|v_t|) F_n (return mapping)
// k is the penalty stiffness of the master segment under the point (penalty.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/contact/contact_options.h"
#include "sim/contact/surface.h"

namespace spallkit::sim::contact {

// One contact point's result: written per slave node (in parallel) or per point contact, and
// scattered to the nodes in a fixed order.
struct ContactSlot {
  int segment = -1;             // master segment in contact; -1: none
  double xi = 0.0;              // its chord parameter
  double fnx = 0.0, fny = 0.0;  // normal force on the slave side
  double ftx = 0.0, fty = 0.0;  // tangential force on the slave side
  double fn = 0.0, penetration = 0.0;
  double stored = 0.0, friction_work = 0.0, damping_work = 0.0;  // J
};

inline double InverseMass(double m) { return m > 0.0 ? 1.0 / m : 0.0; }

// A tangential spring leaving contact: its stored energy 1/2 F^2 / k_t is dissipated (returned)
// and the spring is emptied.
inline double ReleaseSpring(double* force, double stiffness) {
  if (*force == 0.0) return 0.0;
  const double energy = 0.5 * *force * *force / stiffness;
  *force = 0.0;
  return energy;
}

// The kinematics of a contact point that the law needs.
struct ContactKinematics {
  double penetration = 0.0;       // m, > 0 in contact
  double nx = 0.0, ny = 0.0;      // unit normal, pointing at the slave side
  double rvx = 0.0, rvy = 0.0;    // slave velocity relative to the master (m/s)
  double inverse_mass_sum = 0.0;  // 1/m_slave + 1/m_master as the forces are spread (1/kg)
};

// A point's friction spring: its force along the tangent t = (-ny, nx) and its stiffness.
struct StickSpring {
  double* force;
  double* stiffness;
};

class ContactLaw {
 public:
  explicit ContactLaw(const ContactPairOptions& options) : options_(options) {}

  // The mass / time-step penalty law's reference step (the first step's or the option's).
  void set_reference_time_step(double dt) { reference_dt_ = dt; }
  double reference_time_step() const { return reference_dt_; }

  // Penalty stiffness (N/m) of master segment `segment` against the lighter of the two masses.
  double SegmentStiffness(const ContactSurface& master,
                          int segment,
                          double slave_mass,
                          double master_mass) const {
    switch (options_.penalty_law) {
      case PenaltyLaw::kBulkModulus:
        return options_.penalty_scale * master.bulk_stiffness[segment];
      case PenaltyLaw::kMassTimeStep: {
        constexpr double kInf = std::numeric_limits<double>::infinity();
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

  // Normal penalty with damping and the stick spring (updated) capped by Coulomb: fills the
  // slot's forces and energies.
  void Apply(
      double k, const ContactKinematics& p, double dt, StickSpring spring, ContactSlot* slot) const;

 private:
  ContactPairOptions options_;
  double reference_dt_ = 0.0;
};

}  // namespace spallkit::sim::contact
