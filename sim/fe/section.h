// Material and section of a 2-D part: linear elastic, plane strain or plane stress, thickness,
// and the element controls (hourglass stiffness). One Section per mesh part.
#pragma once

#include <cmath>
#include <string>

namespace spallkit::sim::fe {

enum class PlaneMode { kPlaneStrain, kPlaneStress };

struct ElasticMaterial {
  double youngs_modulus = 210e9;  // Pa
  double poisson_ratio = 0.3;
  double density = 7850.0;  // kg/m^3

  double Lambda() const {
    return youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
  double Mu() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
};

struct Section {
  ElasticMaterial material;
  PlaneMode mode = PlaneMode::kPlaneStrain;
  // Out-of-plane thickness (m). Masses and forces are for the whole thickness, also in plane
  // strain (a bearing of width 20 mm: thickness 0.02).
  double thickness = 1.0;
  // Hourglass stiffness scale QM. 1 gives the exact pure-bending stiffness of a square element
  // (see docs/FE.md); elements of aspect ratio r bend about (1 + r^2) / (2 r) times too stiff in
  // their long direction and too soft in the short one.
  double hourglass_coefficient = 1.0;

  // In-plane Lame constant: lambda for plane strain, 2 lambda mu / (lambda + 2 mu) for plane
  // stress (sigma_zz = 0 eliminated).
  double PlaneLambda() const {
    const double l = material.Lambda(), m = material.Mu();
    return mode == PlaneMode::kPlaneStrain ? l : 2.0 * l * m / (l + 2.0 * m);
  }
  // Dilatational wave speed used for the stable step: sqrt((lambda + 2 mu) / rho) in plane strain,
  // sqrt(E / (rho (1 - nu^2))) in plane stress.
  double WaveSpeed() const {
    return std::sqrt((PlaneLambda() + 2.0 * material.Mu()) / material.density);
  }
  // Modulus of a bent fibre with free lateral faces: E in plane stress, E / (1 - nu^2) in plane
  // strain.
  double BendingModulus() const {
    const double nu = material.poisson_ratio;
    return mode == PlaneMode::kPlaneStress ? material.youngs_modulus
                                           : material.youngs_modulus / (1.0 - nu * nu);
  }

  // Empty when valid; otherwise names the bad field.
  bool IsValid(std::string* error) const {
    auto fail = [&](const char* m) {
      if (error) *error = m;
      return false;
    };
    if (!(material.youngs_modulus > 0)) return fail("section: youngs_modulus must be > 0");
    if (!(material.poisson_ratio > -1.0 && material.poisson_ratio < 0.5))
      return fail("section: poisson_ratio must be in (-1, 0.5)");
    if (!(material.density > 0)) return fail("section: density must be > 0");
    if (!(thickness > 0)) return fail("section: thickness must be > 0");
    if (!(hourglass_coefficient >= 0)) return fail("section: hourglass_coefficient must be >= 0");
    return true;
  }
};

}  // namespace spallkit::sim::fe
