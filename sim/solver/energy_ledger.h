// The solver's energy books: the global balance (Energies) and, as a diagnostic, one work
// account per force contributor (WorkLedger, SolverOptions::track_contributor_work) that finds
// which contact pair or constraint creates energy when the balance fails.
#pragma once

#include <string>
#include <vector>

#include "sim/fe/nodal_state.h"
#include "sim/fe/quad_elements.h"
#include "sim/solver/force_contributor.h"

namespace spallkit::sim::solver {

// Energy terms (J), cumulative since t = 0, at the last completed step.
struct Energies {
  // At t^n, the time of the stored energies: 1/2 m v^(n+1/2)^2 (rigid-body extra masses
  // included) less the last half step of the nodal forces' work (explicit_solver.cc).
  double kinetic = 0.0;
  // The same measure at t^0: 1/2 m (v^0)^2 less 1/2 m (dt/2 a^0)^2 for the half-step start.
  double initial_kinetic = 0.0;
  // Contributors' stored energy at the first step: initial overlaps (e.g. a roller vertex that
  // starts inside a race facet's sag) start with penalty energy, part of the initial energy.
  double initial_stored = 0.0;
  double internal = 0.0;  // elastic strain energy (elements)
  double hourglass = 0.0;
  double contact = 0.0;         // stored by contributors (penalty springs)
  double friction = 0.0;        // dissipated by contributors
  double damping = 0.0;         // mass + stiffness damping dissipation
  double external = 0.0;        // applied loads + prescribed-motion (reaction) work
  double external_loads = 0.0;  //   of which applied loads (rigid-body forces + contributors)
  // |E_kin + E_int + E_hg + E_contact + E_fric + E_damp - E_kin(0) - E_contact(0) - W_ext| /
  // Scale().
  double BalanceError() const;
  // The largest energy term's magnitude (initial kinetic included), J: BalanceError's scale.
  double Scale() const;
};

// One contributor's (or the elements') energy account since the ledger started (t = 0, or the
// first step after a resume from a checkpoint; the ledger itself is not checkpointed), J. `work` is
// the work its forces did on the nodes, sum_k f^k . (v^(k-1/2) + v^(k+1/2)) dt_avg / 2 up to t^n
// (the last step's force over its first half step only: the time of the balance's stored
// energies), `velocity_edit` the kinetic energy its direct edits of
// velocities changed (projections, ties). Its own books say the energy went into `stored`, was
// `dissipated` or came in as `external` work; what they do not explain is Created():
//   Created = work + velocity_edit + (stored - initial_stored) + dissipated - external
// (> 0: energy created; initial_stored: its stored energy when the ledger started; dissipated and
// external are counted from then on too).
// For the elements stored = internal + hourglass and dissipated = stiffness damping.
struct ContributorLedger {
  std::string name;
  double work = 0.0, velocity_edit = 0.0;
  double stored = 0.0, initial_stored = 0.0, dissipated = 0.0, external = 0.0;
  double Created() const {
    return work + velocity_edit + stored - initial_stored + dissipated - external;
  }
};

// The ledgers sorted by |Created()|, largest first, as a table of at most max_rows rows plus the
// total (one line each, J).
std::string LedgerReport(std::vector<ContributorLedger> ledgers, int max_rows = 10);

// The work accounts of the elements [0] and of each contributor [1 + c]. Costs two copies of the
// nodal forces per contributor per step.
class WorkLedger {
 public:
  // Step n, in place of the solver's contributor pass: the element forces are already gathered
  // into state.fx / fy; runs every contributor's AddForces in order (serially) and records the
  // forces each one added and the kinetic energy its velocity edits changed.
  void AddForces(fe::NodalState& state,
                 const fe::QuadElements& elements,
                 const std::vector<ForceContributor*>& contributors,
                 double t,
                 double dt);
  // After the nodal update to v^(n+1/2): books the recorded forces' work over the step.
  void BookWork(const fe::NodalState& state, double dt_avg);
  // One account per row (elements first); empty before the first AddForces.
  std::vector<ContributorLedger> Ledgers(const fe::QuadElements& elements,
                                         const std::vector<ForceContributor*>& contributors) const;

 private:
  std::vector<std::vector<double>> force_;  // per account: x then y, 2 x nodes
  std::vector<double> work_, edit_;
  std::vector<double> half_;             // the last step's second half of work_ (t^n to t^(n+1/2))
  std::vector<ContributorLedger> base_;  // accounts when the ledger started
  std::vector<double> vx_, vy_, scratch_;
};

}  // namespace spallkit::sim::solver
