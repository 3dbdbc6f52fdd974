// Penalty stiffness laws for node-to-segment contact.
//
// Two laws, as in LS-DYNA / OpenRadioss (see docs/CONTACT.md):
//  - kBulkModulus (LS-DYNA SOFT=0, OpenRadioss 2-D interfaces, starter i3sti2.F):
//        k = f * K * L_seg^2 / A_elem * t     (N/m)
//    K bulk modulus of the master element behind the segment, L_seg segment length, A_elem that
//    element's area, t the section thickness, f the scale factor (SLSFAC, default 0.1). Per unit
//    thickness this is a stress over a length: the spring of a slab of depth A/L with modulus f*K.
//  - kMassTimeStep (LS-DYNA SOFT=1-like):
//        k = s * m* / dt^2,   m* = min(slave nodal mass, master segment mass)
//    with s the scale factor (SOFSCL-like). For this law (omega * dt)^2 = s * m* (1/m_s + 1/m_m)
//    <= 2 s, so it can never destabilise the step for s < 2; it is what to use between bodies of
//    very different stiffness. dt is the reference step fixed when the pair starts.
//  - kConstant: a given k (N/m) per slave node, for rigid analytic surfaces and unit tests.
#pragma once

#include <string>

namespace spallkit::sim::contact {

enum class PenaltyLaw { kBulkModulus, kMassTimeStep, kConstant };

std::string PenaltyLawToString(PenaltyLaw law);
// Accepts "bulk_modulus", "mass_time_step", "constant"; false on anything else.
bool StringToPenaltyLaw(const std::string& text, PenaltyLaw* law);

// k = scale * K * L^2 / A * thickness (N/m).
inline double BulkModulusPenalty(double scale,
                                 double bulk_modulus,
                                 double segment_length,
                                 double element_area,
                                 double thickness) {
  return scale * bulk_modulus * segment_length * segment_length / element_area * thickness;
}

// k = scale * m* / dt^2 (N/m).
inline double MassTimeStepPenalty(double scale, double effective_mass, double dt) {
  return scale * effective_mass / (dt * dt);
}

// Bulk modulus of an isotropic elastic material, K = E / (3 (1 - 2 nu)).
inline double BulkModulus(double youngs_modulus, double poisson_ratio) {
  return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio));
}

}  // namespace spallkit::sim::contact
