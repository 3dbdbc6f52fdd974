// The hybrid bearing model's force contributor (docs/BEARING_MODEL.md): the rigid
// rollers, cage and inner ring of roller_contacts.h against the FE outer ring's raceway nodes
// (raceway_kernel.h). The outer ring and the adapter (the transfer path to the sensor) stay
// flexible FE; sim/bearing/model_builder.h builds both halves when the scene says
// model.fidelity = "hybrid". The rigid bodies are advanced inside AddForces with the solver's
// step; the solver counts only nodal kinetic energy, so StoredEnergy() adds theirs.
#pragma once

#include <memory>
#include <string>

#include "sim/bearing/raceway_kernel.h"
#include "sim/bearing/roller_contacts.h"
#include "sim/solver/force_contributor.h"

namespace spallkit::sim {

// The FE outer ring as the rollers' outer race: gap, normal and velocity from the raceway
// kernel over the current nodal state; reactions spread onto the raceway nodes.
class FeOuterRace : public OuterRace {
 public:
  explicit FeOuterRace(const RacewayKernel& kernel) : kernel_(kernel) {}
  void Bind(fe::NodalState* state) { state_ = state; }

  void Gap(double qx, double qy, double rad, RacePoint* p) const override;
  void Velocity(double px, double py, double* vx, double* vy) const override;
  void Apply(double px, double py, double fx, double fy) override;

 private:
  const RacewayKernel& kernel_;
  fe::NodalState* state_ = nullptr;
};

class HybridRollers : public solver::ForceContributor {
 public:
  using Body = PlanarBody;

  // `housing`: the mesh from MeshBearingHousing (its "outer_ring.raceway" curve must have
  // uniformly spaced nodes); `state`: the solver's nodal state (masses set). Throws InputError.
  HybridRollers(const Scene& scene,
                const BearingMesh& housing,
                const fe::NodalState& state,
                const HybridOptions& options,
                const CageGuideOptions& cage_guide);

  void AddForces(fe::NodalState& state, double t, double dt) override;
  double StableTimeStep(const fe::NodalState& /*state*/) const override {
    return rollers_->StableTimeStep();
  }
  double StoredEnergy() const override { return rollers_->StoredEnergy(); }
  double DissipatedEnergy() const override { return rollers_->DissipatedEnergy(); }
  double ExternalWork() const override { return rollers_->ExternalWork(); }
  std::string Name() const override { return "hybrid_rollers"; }
  std::string SaveState() const override { return rollers_->SaveState(); }
  void LoadState(const std::string& bytes) override { rollers_->LoadState(bytes); }

  const RollerContacts& rollers() const { return *rollers_; }
  const RacewayKernel& kernel() const { return kernel_; }

 private:
  RacewayKernel kernel_;
  FeOuterRace race_;
  std::unique_ptr<RollerContacts> rollers_;
};

}  // namespace spallkit::sim
