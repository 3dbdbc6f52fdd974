#include "sim/solver/energy_ledger.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace spallkit::sim::solver {

double Energies::BalanceError() const {
  const double total = kinetic + internal + hourglass + contact + friction + damping;
  const double err = std::abs(total - initial_kinetic - initial_stored - external);
  const double scale = Scale();
  return scale > 0.0 ? err / scale : 0.0;
}

double Energies::Scale() const {
  double scale = initial_kinetic;
  for (double v :
       {kinetic, internal, hourglass, contact, friction, damping, external, initial_stored})
    scale = std::max(scale, std::abs(v));
  return scale;
}

std::string LedgerReport(std::vector<ContributorLedger> ledgers, int max_rows) {
  std::stable_sort(ledgers.begin(), ledgers.end(), [](const auto& a, const auto& b) {
    return std::abs(a.Created()) > std::abs(b.Created());
  });
  double total = 0.0;
  for (const ContributorLedger& l : ledgers) total += l.Created();
  std::ostringstream os;
  os << "energy ledger (J; created = work + velocity edits + stored + dissipated - external), "
     << "total created " << total;
  char buf[256];
  for (int i = 0; i < static_cast<int>(ledgers.size()) && i < max_rows; ++i) {
    const ContributorLedger& l = ledgers[i];
    std::snprintf(buf,
                  sizeof buf,
                  "\n  %-40s created %+10.3e  work %+10.3e  stored %10.3e  dissipated %10.3e",
                  l.name.c_str(),
                  l.Created(),
                  l.work + l.velocity_edit,
                  l.stored,
                  l.dissipated);
    os << buf;
  }
  return os.str();
}

void WorkLedger::AddForces(fe::NodalState& state,
                           const fe::QuadElements& elements,
                           const std::vector<ForceContributor*>& contributors,
                           double t,
                           double dt) {
  const size_t nn = state.size();
  const size_t n = 1 + contributors.size();
  const bool first = force_.size() != n;  // t = 0, or the first step after a resume
  if (first) {
    force_.assign(n, std::vector<double>(2 * nn, 0.0));
    work_.assign(n, 0.0), half_.assign(n, 0.0), edit_.assign(n, 0.0);
    base_.assign(n, ContributorLedger{});
    scratch_.assign(2 * nn, 0.0);
    // Baselines: the accounts start here (stored energy at x^n; cumulative terms so far).
    base_[0].stored = elements.InternalEnergy() + elements.HourglassEnergy();
    base_[0].dissipated = elements.DampingEnergy();
    for (size_t c = 0; c < contributors.size(); ++c) {
      base_[1 + c].dissipated = contributors[c]->DissipatedEnergy();
      base_[1 + c].external = contributors[c]->ExternalWork();
    }
  }
  auto kinetic = [&] {
    double k = 0.0;
    for (size_t i = 0; i < nn; ++i)
      k += 0.5 * state.mass[i] * (state.vx[i] * state.vx[i] + state.vy[i] * state.vy[i]);
    return k;
  };
  std::copy(state.fx.begin(), state.fx.end(), force_[0].begin());
  std::copy(state.fy.begin(), state.fy.end(), force_[0].begin() + nn);
  for (size_t c = 0; c < contributors.size(); ++c) {
    std::copy(state.fx.begin(), state.fx.end(), scratch_.begin());
    std::copy(state.fy.begin(), state.fy.end(), scratch_.begin() + nn);
    const double k0 = kinetic();
    contributors[c]->AddForces(state, t, dt);
    edit_[1 + c] += kinetic() - k0;
    if (first) base_[1 + c].stored = contributors[c]->StoredEnergy();
    std::vector<double>& f = force_[1 + c];
    for (size_t i = 0; i < nn; ++i) {
      f[i] = state.fx[i] - scratch_[i];
      f[nn + i] = state.fy[i] - scratch_[nn + i];
    }
  }
  vx_ = state.vx, vy_ = state.vy;  // v^(n-1/2) as the update sees it
}

void WorkLedger::BookWork(const fe::NodalState& state, double dt_avg) {
  const size_t nn = state.size();
  for (size_t c = 0; c < force_.size(); ++c) {
    const std::vector<double>& f = force_[c];
    double w = 0.0, second = 0.0;
    for (size_t i = 0; i < nn; ++i) {
      w += f[i] * vx_[i] + f[nn + i] * vy_[i];
      second += f[i] * state.vx[i] + f[nn + i] * state.vy[i];
    }
    work_[c] += 0.5 * dt_avg * (w + second);
    half_[c] = 0.5 * dt_avg * second;
  }
}

std::vector<ContributorLedger> WorkLedger::Ledgers(
    const fe::QuadElements& elements, const std::vector<ForceContributor*>& contributors) const {
  std::vector<ContributorLedger> out;
  if (work_.empty()) return out;
  auto account =
      [&](size_t k, std::string name, double stored, double dissipated, double external) {
        ContributorLedger l;
        l.name = std::move(name);
        l.work = work_[k] - half_[k], l.velocity_edit = edit_[k];
        l.stored = stored, l.initial_stored = base_[k].stored;
        l.dissipated = dissipated - base_[k].dissipated;
        l.external = external - base_[k].external;
        out.push_back(l);
      };
  account(0,
          "elements",
          elements.InternalEnergy() + elements.HourglassEnergy(),
          elements.DampingEnergy(),
          0.0);
  for (size_t c = 0; c < contributors.size(); ++c) {
    const ForceContributor* f = contributors[c];
    account(1 + c, f->Name(), f->StoredEnergy(), f->DissipatedEnergy(), f->ExternalWork());
  }
  return out;
}

}  // namespace spallkit::sim::solver
