// The raceway kernel: how a rigid roller's contact meets the FE outer ring's raceway nodes.
//
// The race surface radius at angle theta is the reference raceway radius plus the radial nodal
// displacement averaged with a cubic B-spline kernel of half-width L (arc length) around theta;
// a contact force goes to the same nodes with the same weights (work conjugate). Spreading over
// L (>= 1 mm, >= 2 node spacings) makes the force independent of where the contact sits between
// nodes; the ring's elastic response to a load spread over 2L is its structural compliance, the
// Hertzian part is in the Palmgren constant. The B-spline is C2, so the weights change smoothly
// as a contact crosses a node (docs/BEARING_MODEL.md, "The hybrid model").
#pragma once

#include <string>
#include <vector>

#include "sim/fe/mesh.h"
#include "sim/fe/nodal_state.h"

namespace spallkit::sim {

class RacewayKernel {
 public:
  static constexpr int kMaxNodes = 64;

  // `curve`: a closed curve of `mesh` on a circle of radius `raceway_radius` (m) with uniformly
  // spaced nodes; `half_width` L (m), 0: the larger of 1 mm and 2 node spacings. Throws
  // InputError when the curve is missing, has fewer than 8 nodes or is not uniform.
  RacewayKernel(const fe::Mesh& mesh,
                const std::string& curve,
                double raceway_radius,
                double half_width);

  // Weights of the raceway nodes around angle th: indices into nodes() and weights (sum 1);
  // with dw != nullptr also the weights' derivatives dw_i/dth. Returns the count.
  int Weights(double th, int* idx, double* w, double* dw = nullptr) const;
  // Deformed raceway radius at angle th (reference radius + kernel-averaged radial
  // displacement) and, when slope != nullptr, its derivative dR/dth (m/rad).
  double Radius(const fe::NodalState& s, double th, double* slope = nullptr) const;
  // Kernel-averaged velocity of the raceway at angle th.
  void Velocity(const fe::NodalState& s, double th, double* vx, double* vy) const;
  // Adds the force (fx, fy) acting at angle th to the kernel's nodes.
  void Spread(fe::NodalState& s, double th, double fx, double fy) const;
  // Effective mass of the raceway under one contact's kernel, 1 / max sum_i w_i^2 / m_i (kg),
  // taken at its smallest over the kernel's positions around the ring and between two nodes.
  double ContactMass(const fe::NodalState& s) const;

  double half_width() const { return half_width_; }
  double radius() const { return radius_; }
  const std::vector<int>& nodes() const { return nodes_; }  // sorted by reference angle

 private:
  double radius_ = 0, half_width_ = 0, theta0_ = 0, dtheta_ = 0;
  std::vector<int> nodes_;
  std::vector<double> ex_, ey_;  // radial unit vectors of the nodes
};

}  // namespace spallkit::sim
