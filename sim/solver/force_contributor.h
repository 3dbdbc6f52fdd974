// Anything besides the element internal forces that pushes on nodes: contact pairs, rigid
// constraints with applied loads, external loads. The explicit solver calls every contributor
// once per step after the element forces, in a fixed order (deterministic results).
#pragma once

#include <limits>
#include <string>

#include "sim/fe/nodal_state.h"

namespace spallkit::solver {

class ForceContributor {
 public:
  virtual ~ForceContributor() = default;

  // Adds forces at time t (positions x^n, velocities v^(n-1/2)) into state.fx / state.fy.
  // dt is the step about to be taken (n -> n+1).
  virtual void AddForces(fe::NodalState& state, double t, double dt) = 0;

  // Largest time step this contributor tolerates (e.g. contact stiffness against nodal mass).
  virtual double StableTimeStep(const fe::NodalState& /*state*/) const {
    return std::numeric_limits<double>::infinity();
  }

  // Energy terms for the balance, cumulative since t = 0 (J).
  virtual double StoredEnergy() const { return 0.0; }      // e.g. penalty spring energy
  virtual double DissipatedEnergy() const { return 0.0; }  // e.g. friction work
  virtual double ExternalWork() const { return 0.0; }      // work of applied loads

  virtual std::string Name() const = 0;

  // Checkpoint/restart (added by fe): a contributor with history (friction springs, cumulative
  // energies) returns it as bytes and restores it, so that a resumed run is identical to an
  // uninterrupted one. The default has no state.
  virtual std::string SaveState() const { return {}; }
  virtual void LoadState(const std::string& /*bytes*/) {}
};

}  // namespace spallkit::solver
