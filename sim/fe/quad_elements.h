// One-point 4-node quadrilaterals with Flanagan-Belytschko stiffness hourglass control, for the
// explicit solver.
//
// Formulation (details and references in docs/FE.md):
//  - Uniform-strain (centroid) kinematics. The rate of deformation over a step is taken from the
//    velocities v^(n-1/2) on the MID-STEP geometry x^(n-1/2) = x^n - dt/2 v^(n-1/2): for a rigid
//    rotation this velocity gradient is exactly skew, so a spinning body strains nothing.
//  - Hypoelastic linear-elastic stress with an objective (Jaumann) rate, integrated with the
//    Hughes-Winget rotation (exactly orthogonal): stresses and hourglass forces rotate with the
//    material and rings can spin for hundreds of revolutions without spurious stress.
//  - Hourglass: gamma-projected mode (orthogonal to linear fields, so the patch test passes on
//    distorted meshes) with a co-rotational stiffness  Q += kappa * qdot * dt, kappa =
//    QM * (2/3) E' t A (b.b), which is the exact pure-bending stiffness of a square element.
//  - Optional stiffness-proportional damping: a viscous stress beta C:D (not stored).
//  - Stable step per element: L_e / c with L_e = A / max(4 sides, 2 diagonals), computed in the
//    same pass as the forces, on the current geometry.
//
// Data are structure-of-arrays; elements are processed in fixed blocks of one part (so section
// constants are scalars in the inner loop). Each element writes its 4 corner forces into its own
// slots; nodes gather them through a CSR map in a fixed order, so results are bit-identical for
// any number of OpenMP threads. No allocation after construction.
#pragma once

#include <cstdint>
#include <vector>

#include "core/checkpoint_io.h"
#include "sim/fe/mesh.h"
#include "sim/fe/nodal_state.h"
#include "sim/fe/section.h"

namespace spallkit::sim::fe {

class QuadElements {
 public:
  // Elements per block (and per energy accumulator). Fixed, so that sums do not depend on
  // the thread count.
  static constexpr int kBlockSize = 256;
  // Nodes per gather chunk (the unit of OpenMP work in GatherForces / ComputeForces).
  static constexpr int kGatherChunk = 1024;

  // One Section per mesh part. Throws InputError for an invalid mesh or section.
  QuadElements(const Mesh& mesh, std::vector<Section> sections);

  int num_elements() const { return static_cast<int>(n1_.size()); }
  int num_nodes() const { return num_nodes_; }
  int num_parts() const { return static_cast<int>(sections_.size()); }
  const Section& section(int part) const { return sections_[part]; }
  int element_part(int e) const { return part_[e]; }

  // Adds the lumped mass rho * A * t / 4 of every element (reference geometry) to state->mass.
  void AddLumpedMass(NodalState* state) const;

  // Stiffness-proportional damping coefficient beta (s): viscous stress beta * C : D.
  void set_stiffness_damping(double beta) { beta_ = beta; }
  double stiffness_damping() const { return beta_; }

  // Keep the internal, hourglass and stiffness-damping energies (default). Off, the element
  // pass skips their sums (stresses and forces are bit-identical) and the energies read NaN.
  void set_energy_terms(bool on) { energy_terms_ = on; }
  bool energy_terms() const { return energy_terms_; }

  // Element pass of step n. Updates stress and hourglass state with v^(n-1/2) over dt_prev
  // (0 on the first step), writes the corner forces for positions x^n, and returns the
  // smallest element stable step (without safety factor; reduced for stiffness damping).
  // Throws NumericalError if an element inverts. Runs on `threads` OpenMP threads (0: default).
  double ComputeCornerForces(const NodalState& state, double dt_prev, int threads);

  // ComputeCornerForces followed by GatherForces(state, threads) in ONE OpenMP parallel region
  // (one fork/join per step instead of two; identical results).
  double ComputeForces(NodalState* state, double dt_prev, int threads);

  // The pieces of ComputeCornerForces, for callers that run their own OpenMP region (the solver
  // fuses its node loops into the element pass): ComputeBlock(k, ...) once for every k in
  // [0, num_blocks()), in any order on any thread, then StableStep(state) (serial; throws
  // NumericalError if an element inverted).
  int num_blocks() const { return static_cast<int>(blocks_.size()); }
  void ComputeBlock(int k, const NodalState& state, double dt_prev);
  double StableStep(const NodalState& state) const;

  // state->fx/fy = - sum of the corner forces of each node (overwrites; fixed order).
  void GatherForces(NodalState* state, int threads) const;
  // Same for nodes [begin, end) only, for callers that fuse the gather with their own node loop.
  void GatherForces(NodalState* state, int begin, int end) const;

  // Energies (J), cumulative since t = 0, summed over blocks in a fixed order.
  double InternalEnergy() const;
  double HourglassEnergy() const;
  double DampingEnergy() const;  // stiffness-damping dissipation
  double InternalEnergy(int part) const;
  double HourglassEnergy(int part) const;

  // Element stress (Pa) at the centroid, global axes.
  double sxx(int e) const { return sxx_[e]; }
  double syy(int e) const { return syy_[e]; }
  double sxy(int e) const { return sxy_[e]; }
  double szz(int e) const { return szz_[e]; }
  double VonMises(int e) const;
  // Current area of element e (m^2) and its centroid.
  double Area(const NodalState& state, int e) const;
  void Centroid(const NodalState& state, int e, double* x, double* y) const;
  const std::vector<int>& connectivity(int corner) const;  // node ids of corner 0..3

  // Raw element state for checkpoints.
  void Save(CheckpointWriter* out) const;
  void Load(CheckpointReader* in);

 private:
  struct Block {
    int begin, end, part;
  };
  // Returns the block's largest (c / L_e)^2 (not yet reduced for stiffness damping), or
  // +infinity if an element is inverted.
  template <bool kStiffDamp, bool kEnergy>
  double BlockKernel(
      const Block& b, const NodalState& s, double h, double* e_int, double* e_hg, double* e_damp);

  int num_nodes_ = 0;
  std::vector<Section> sections_;
  std::vector<Block> blocks_;
  std::vector<int> part_;
  std::vector<int> n1_, n2_, n3_, n4_;         // connectivity, SoA
  std::vector<double> sxx_, syy_, sxy_, szz_;  // stress
  std::vector<double> qx_, qy_;                // hourglass generalized forces
  std::vector<double> fcx_, fcy_;              // corner forces, [corner * ne + e]
  std::vector<int> node_ptr_, node_slots_;     // CSR node -> corner slots, ascending
  std::vector<int> gather4_;  // per node its first 4 slots, padded with the zero slot 4 * ne
  std::vector<int> overflow_node_, overflow_slot_;         // slots 5, 6, ... (node ascending)
  std::vector<double> block_int_, block_hg_, block_damp_;  // cumulative energies per block
  std::vector<double> block_inv_dt_, block_min_area_;      // per-pass scratch ((c/L_e)^2)
  double beta_ = 0.0;
  bool energy_terms_ = true;
};

}  // namespace spallkit::sim::fe
