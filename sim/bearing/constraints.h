// Two kinematic constraints the bearing section needs and the explicit solver does not offer,
// written as ForceContributors (added LAST, after every contact pair, so that they see the full
// nodal force):
//
//  - RigidPart: a node set that moves as ONE rigid body with free translation AND free rotation
//    (the solver's RigidBody prescribes the rotation). Used for the cage: in the 2-D section the
//    through-pockets cut the cage into Z webs whose joining side rims lie outside the plane, so
//    the webs are made one rigid body (docs/BEARING_MODEL.md). Each step it takes
//    the resultant F and torque T (about the mass centre c) of the forces on the set, and
//    replaces the force on node i by m_i (F / M + alpha e_z x r_i - omega^2 r_i), alpha = T / J,
//    r_i = x_i - c: the exact rigid acceleration (translation, angular acceleration,
//    centripetal). Resultant and torque are unchanged, so the constraint does no work on a rigid
//    velocity field; the work it does do (rounding, the centripetal term's O(dt^2) error) is
//    reported as ExternalWork() so the energy balance shows it. First, positions and
//    velocities are projected onto the best-fit rigid motion of the reference shape (no drift
//    over thousands of revolutions; momentum and angular momentum unchanged).
//
//  - TiedNodes: pairs of coincident nodes of two parts (outer ring outside / adapter seat) that
//    move together. Each step the pair's velocities and positions are set to their
//    mass-weighted means (momentum conserving) and the pair's total force is shared in
//    proportion to mass, so both get the same acceleration. The averaging removes the tiny
//    velocity difference left by part-relative mass damping; the kinetic energy it removes is
//    reported as DissipatedEnergy().
//
//  - CagePocketGuide: the roller-guided cage's radial retention (CageGuideOptions below).
//
// None keeps history besides cumulative energies, which SaveState/LoadState carry.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sim/solver/force_contributor.h"

namespace spallkit::sim {

class RigidPart : public solver::ForceContributor {
 public:
  // nodes: the rigid set (>= 2 nodes, not all coincident). The masses are read at the first step.
  RigidPart(std::string name, std::vector<int> nodes);

  void AddForces(fe::NodalState& state, double t, double dt) override;
  double ExternalWork() const override { return work_; }
  std::string Name() const override { return name_; }
  std::string SaveState() const override;
  void LoadState(const std::string& bytes) override;

  // Rigid motion of the set from positions x^n and velocities v^(n-1/2) (any time).
  struct Motion {
    double cx = 0, cy = 0;         // mass centre, m
    double vx = 0, vy = 0;         // mass-centre velocity, m/s
    double omega = 0;              // spin, rad/s (counter-clockwise)
    double mass = 0, inertia = 0;  // kg, kg m^2 about the mass centre
  };
  Motion ComputeMotion(const fe::NodalState& state) const;
  const std::vector<int>& nodes() const { return nodes_; }

 private:
  std::string name_;
  std::vector<int> nodes_;
  std::vector<double> ref_x_, ref_y_;  // reference shape about the mass centre
  double work_ = 0.0;
};

// Roller-guided cage (every model, the same assumption): each pocket holds its roller's centre
// within +-radial_play of the pitch radius, measured along the pocket's centre line in the cage
// frame; beyond, a linear spring. Straight pocket walls alone leave the cage free to drift
// radially with the rollers sliding along their orbits (hybrid: cage centre 12 mm off; full FE:
// 1.9 mm in 5 ms at 6000 rpm, until the webs' corners struck the rollers). The play bounds how
// far off-centre the cage runs, so it sets the rollers' uneven spacing (docs/BEARING_MODEL.md).
// A BearingModel takes it from the scene (bearing.cage_radial_play_mm).
struct CageGuideOptions {
  double radial_play_m = 0.5e-3;
  double stiffness_n_per_m = 2e8;  // whole section

  bool IsValid(std::string* error) const;
  // Force on the roller along the pocket's centre line (N, towards the play band) for a roller
  // centre `radial` m off the pitch radius; adds the spring's energy to *energy.
  double RadialForce(double radial, double* energy) const;
};

// The FE model's cage guide: spring forces between each roller's mass centre (on its nodes, in
// proportion to mass: no torque on the roller) and the cage (on the cage nodes as the force and
// torque of the same force at the roller's centre; the cage's RigidPart, added after this,
// makes them rigid-body accelerations). The force is the exact gradient of
//   V = sum_j 1/2 k max(0, |(c_j - c_cage) . e_j - R_pitch| - play)^2,
// e_j = unit vector from the cage's mass centre to the mass centre of pocket j's wall nodes
// (it turns with the cage), so it does no net work over a cycle (StoredEnergy() = V).
class CagePocketGuide : public solver::ForceContributor {
 public:
  // rollers[j] / pockets[j]: node sets of roller j and of the walls of its pocket; cage: every
  // cage node. Throws InputError for empty sets or invalid options.
  CagePocketGuide(std::string name,
                  std::vector<std::vector<int>> rollers,
                  std::vector<std::vector<int>> pockets,
                  std::vector<int> cage,
                  double pitch_radius_m,
                  const CageGuideOptions& options);

  void AddForces(fe::NodalState& state, double t, double dt) override;
  double StableTimeStep(const fe::NodalState& state) const override;
  double StoredEnergy() const override { return potential_; }
  std::string Name() const override { return name_; }
  // Radial force on roller j at the last step (N, >= 0; 0 inside the play).
  double Force(int j) const { return force_[j]; }

 private:
  std::string name_;
  std::vector<std::vector<int>> rollers_, pockets_;
  std::vector<int> cage_;
  double pitch_radius_ = 0.0;
  CageGuideOptions options_;
  double potential_ = 0.0;
  std::vector<double> force_;
  mutable double stable_step_ = 0.0;  // 0: not yet computed
};

class TiedNodes : public solver::ForceContributor {
 public:
  // Pairs (a, b) of node ids; each node in at most one pair.
  TiedNodes(std::string name, std::vector<std::pair<int, int>> pairs);

  void AddForces(fe::NodalState& state, double t, double dt) override;
  double DissipatedEnergy() const override { return dissipated_; }
  std::string Name() const override { return name_; }
  std::string SaveState() const override;
  void LoadState(const std::string& bytes) override;
  int num_pairs() const { return static_cast<int>(pairs_.size()); }

 private:
  std::string name_;
  std::vector<std::pair<int, int>> pairs_;
  double dissipated_ = 0.0;
};

}  // namespace spallkit::sim
