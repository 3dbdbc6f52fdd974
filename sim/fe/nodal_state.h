// Nodal state of an explicit 2-D model, structure of arrays.
//
// This is the contract between the element kernels (sim/fe), the contact module (sim/contact)
// and the time integrator (sim/solver): every force producer reads positions and velocities from
// here and adds into fx/fy. Units are SI; forces are for the whole section thickness.
#pragma once

#include <cstddef>
#include <vector>

namespace spallkit::sim::fe {

struct NodalState {
  std::vector<double> x0, y0;  // reference (initial) coordinates, m
  std::vector<double> x, y;    // current coordinates x^n, m
  std::vector<double> vx, vy;  // velocities v^(n-1/2), m/s
  std::vector<double> fx, fy;  // force accumulators at step n, N (zeroed by the solver each step)
  std::vector<double> mass;    // lumped nodal mass, kg

  std::size_t size() const { return x.size(); }
  void Resize(std::size_t n) {
    for (auto* v : {&x0, &y0, &x, &y, &vx, &vy, &fx, &fy, &mass}) v->assign(n, 0.0);
  }
};

}  // namespace spallkit::sim::fe
