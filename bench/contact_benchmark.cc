// Contact cost: ns per slave-node-cycle of ContactPair::AddForces for a roller-like disc rim
// (slave) resting in a bore (master), with friction, and for far-apart pairs (bounding-box
// rejection only); the same rim in the bore with both surfaces marked as circular arcs (curved
// contact: arc search, blend, Jet gradient) and as cubic B-splines (smooth contact: one Newton
// point per step, warm-started). Run: build-<you>/bench/contact_benchmark
#include <benchmark/benchmark.h>

#include <cmath>

#include "sim/contact/contact_pair.h"

namespace {

using namespace spallkit;

// Slave: a circle of n nodes, radius r, centred at (0, -(R - r) - overlap) so that it presses
// into a master bore of radius R (m nodes, walked clockwise so the ring body is outside).
struct Setup {
  sim::fe::NodalState state;
  sim::contact::ContactSurface slave, master;
};

Setup MakeSetup(int n, int m, double offset_y, bool curved) {
  const double r = 5e-3, R = 30e-3, pi = 3.14159265358979;
  Setup s;
  s.state.Resize(n + m);
  std::vector<int> sn(n), mn(m);
  for (int i = 0; i < n; ++i) {
    const double th = 2 * pi * i / n;
    s.state.x[i] = r * std::cos(th);
    s.state.y[i] = -(R - r) - 1e-6 + offset_y + r * std::sin(th);
    s.state.vx[i] = 0.3 * std::sin(th);
    sn[i] = i;
  }
  for (int j = 0; j < m; ++j) {
    const double th = -2 * pi * j / m;
    s.state.x[n + j] = R * std::cos(th);
    s.state.y[n + j] = R * std::sin(th);
    mn[j] = n + j;
  }
  s.state.x0 = s.state.x;
  s.state.y0 = s.state.y;
  s.state.mass.assign(n + m, 1e-4);
  s.slave = sim::contact::MakeSurfaceFromChain("roller", sn, true);
  s.master = sim::contact::MakeSurfaceFromChain("race", mn, true);
  if (curved) {
    const double cy = -(R - r) - 1e-6 + offset_y;
    sim::contact::MarkCircularArcs(
        &s.slave, s.state.x.data(), s.state.y.data(), {0.0, cy, r}, 1e-12);
    sim::contact::MarkCircularArcs(
        &s.master, s.state.x.data(), s.state.y.data(), {0.0, 0.0, R}, 1e-12);
  }
  return s;
}

void Run(benchmark::State& bs, double offset_y, bool curved = false, bool smooth = false) {
  const int n = static_cast<int>(bs.range(0));
  Setup s = MakeSetup(n, 6 * n, offset_y, curved);
  sim::contact::ContactPairOptions o;
  o.penalty_law = sim::contact::PenaltyLaw::kConstant;
  o.constant_stiffness = 1e9;
  o.friction = {.static_coefficient = 0.01, .dynamic_coefficient = 0.005, .decay = 1.0};
  o.smooth_surfaces = smooth;
  sim::contact::ContactPair pair("bench", s.slave, s.master, o);
  for (auto _ : bs) {
    pair.AddForces(s.state, 0.0, 2e-9);
    benchmark::DoNotOptimize(s.state.fx.data());
  }
  bs.counters["ns_per_slave_node_cycle"] = benchmark::Counter(
      static_cast<double>(n),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  bs.counters["active_nodes"] = pair.Resultant().active_nodes;
}

void BM_ContactRollerInBore(benchmark::State& bs) { Run(bs, 0.0); }
void BM_ContactFarApart(benchmark::State& bs) { Run(bs, 0.1); }
void BM_ContactCurvedRollerInBore(benchmark::State& bs) { Run(bs, 0.0, true); }
void BM_ContactSmoothRollerInBore(benchmark::State& bs) { Run(bs, 0.0, true, true); }

BENCHMARK(BM_ContactRollerInBore)->Arg(128)->Arg(512)->Arg(2048);
BENCHMARK(BM_ContactFarApart)->Arg(128)->Arg(512)->Arg(2048);
BENCHMARK(BM_ContactCurvedRollerInBore)->Arg(128)->Arg(512)->Arg(2048);
BENCHMARK(BM_ContactSmoothRollerInBore)->Arg(128)->Arg(512)->Arg(2048);

}  // namespace

BENCHMARK_MAIN();
