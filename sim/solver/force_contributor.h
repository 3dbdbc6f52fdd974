// Anything besides the element internal forces that pushes on nodes: contact pairs, rigid
// constraints with applied loads, external loads. The explicit solver calls every contributor
// once per step after the element forces, in a fixed order (deterministic results).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "sim/fe/nodal_state.h"

namespace spallkit::sim::solver {

// Nodal forces recorded instead of added: (node, fx, fy) in the order they were produced.
// ApplyTo adds them in that order, so a contributor that computes into a log and applies it
// later gives the same sums whichever thread computed it.
class ForceLog {
 public:
  void Clear() { entries_.clear(); }
  void Add(int node, double fx, double fy) { entries_.push_back({node, fx, fy}); }
  void ApplyTo(fe::NodalState& state) const {
    double* fx = state.fx.data();
    double* fy = state.fy.data();
    for (const Entry& e : entries_) fx[e.node] += e.fx, fy[e.node] += e.fy;
  }

 private:
  struct Entry {
    int node;
    double fx, fy;
  };
  std::vector<Entry> entries_;  // capacity kept between steps: no allocation once warm
};

class ForceContributor {
 public:
  virtual ~ForceContributor() = default;

  // Adds forces at time t (positions x^n, velocities v^(n-1/2)) into state.fx / state.fy.
  // dt is the step about to be taken (n -> n+1).
  virtual void AddForces(fe::NodalState& state, double t, double dt) = 0;

  // AddForces in two halves, for contributors that only read the state (x, v, mass) and only add
  // to fx / fy: ComputeForces may run on any thread, concurrently with other such contributors';
  // ApplyForces then adds what it computed, called serially in contributor order. The solver
  // runs the leading contributors that split this way in parallel (ExplicitSolver::Step); the
  // sums are the same for every thread count. AddForces must equal Compute + Apply.
  virtual bool SplitsForces() const { return false; }
  virtual void ComputeForces(const fe::NodalState& /*state*/, double /*t*/, double /*dt*/) {}
  virtual void ApplyForces(fe::NodalState& /*state*/) const {}

  // Largest time step this contributor tolerates (e.g. contact stiffness against nodal mass).
  virtual double StableTimeStep(const fe::NodalState& /*state*/) const {
    return std::numeric_limits<double>::infinity();
  }

  // Energy terms for the balance, cumulative since t = 0 (J).
  virtual double StoredEnergy() const { return 0.0; }      // e.g. penalty spring energy
  virtual double DissipatedEnergy() const { return 0.0; }  // e.g. friction work
  virtual double ExternalWork() const { return 0.0; }      // work of applied loads

  virtual std::string Name() const = 0;

  // Checkpoint/restart: a contributor with history (friction springs, cumulative
  // energies) returns it as bytes and restores it, so that a resumed run is identical to an
  // uninterrupted one. The default has no state.
  virtual std::string SaveState() const { return {}; }
  virtual void LoadState(const std::string& /*bytes*/) {}
};

}  // namespace spallkit::sim::solver
