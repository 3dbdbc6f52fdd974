// Cost of the bearing simulation, hybrid model (sim/bearing/hybrid_rollers.h): wall time per
// simulated millisecond of the paper's verification scene at 6000 rpm with its spall, after the
// speed ramp (the contacts are all live), for housing meshes of 2.0, 1.0, 0.5 and 0.25 mm. One
// iteration = 0.1 ms of simulated time; the counters give ms of wall per simulated ms, the
// time step and ns per element-cycle (elements + hybrid contacts + tie + damping).
// BM_LumpedSimulatedSecond: the lumped model, wall seconds per simulated second at 1200 rpm
// (arguments: traction law or Coulomb, energy books, spall, [solver] lumped_step = "fast").
// Run: build-<you>/bench/bearing_benchmark [--benchmark_min_time=2]
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <vector>

#include "sim/bearing/lumped_model.h"
#include "sim/bearing/model_builder.h"
#include "sim/bearing/scene.h"

namespace {

using namespace spallkit::sim;

void BM_HybridSimulatedMs(benchmark::State& bs) {
  const double mesh_mm = static_cast<double>(bs.range(0)) / 100.0;
  const Scene scene =
      LoadScene(std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml",
                {"model.fidelity=hybrid",
                 "mesh.size_mm=" + std::to_string(mesh_mm),
                 "operation.speed_rpm=6000",
                 "operation.ramp_s=0.0005",
                 "solver.threads=1"});
  FeBearingModel model(scene);
  spallkit::sim::solver::ExplicitSolver& s = model.solver();
  s.Run(0.001);  // past the ramp
  constexpr double kChunk = 1e-4;
  long steps = 0;
  double wall = 0.0;
  for (auto _ : bs) {
    const long s0 = s.step();
    const auto t0 = std::chrono::steady_clock::now();
    s.Run(s.time() + kChunk);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    steps += s.step() - s0;
  }
  const double simulated_ms = bs.iterations() * kChunk * 1e3;
  const double elements = model.bearing_mesh().mesh.num_elements();
  bs.counters["wall_ms_per_sim_ms"] = 1e3 * wall / simulated_ms;
  bs.counters["dt_ns"] = 1e9 * kChunk * bs.iterations() / static_cast<double>(steps);
  bs.counters["elements"] = elements;
  bs.counters["ns_per_element_cycle"] = 1e9 * wall / (static_cast<double>(steps) * elements);
}
BENCHMARK(BM_HybridSimulatedMs)
    ->Arg(200)
    ->Arg(100)
    ->Arg(50)
    ->Arg(25)
    ->Unit(benchmark::kMillisecond)
    ->ArgName("mesh_x100_mm");

// The lumped model (sim/bearing/lumped_model.h) on the same scene at the paper's 1200 rpm, after
// the ramps; the housing fit is made (and cached) before the timing. One iteration = 10 ms of
// simulated time; wall_s_per_sim_s is the figure the fidelity ladder quotes. Argument 0: Coulomb
// friction at 0.15 / 0.12; 1: the paper's 0.01 / 0.005 with the lubricant traction law (the main
// job's friction and the ladder's), whose race contacts have no stick spring to limit the step.
// Second argument: the energy books kept (1, as `spall simulate` does by default) or not (0, a
// scene without the energy output and the energy guard). Third: the scene's spall (1) or the
// same bearing healthy (0, `defects=[]`: no passages, the long step on two springs).
void BM_LumpedSimulatedSecond(benchmark::State& bs) {
  const std::vector<std::string> friction =
      bs.range(0) == 0
          ? std::vector<std::string>{"friction.mu_static=0.15", "friction.mu_dynamic=0.12"}
          : std::vector<std::string>{"friction.model=ehl"};
  std::vector<std::string> sets = {"model.fidelity=lumped"};
  if (bs.range(2) == 0) sets.push_back("defects=[]");
  if (bs.range(3) != 0) sets.push_back("solver.lumped_step=fast");
  sets.insert(sets.end(), friction.begin(), friction.end());
  const Scene scene = LoadScene(
      std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml", sets);
  BearingModelOptions options;
  options.hybrid.energy_books = bs.range(1) != 0;
  LumpedBearingModel model(scene, options);
  model.Run(0.01);  // past the ramps
  constexpr double kChunk = 0.01;
  long steps = 0;
  double wall = 0.0;
  for (auto _ : bs) {
    const long s0 = model.step();
    const auto t0 = std::chrono::steady_clock::now();
    model.Run(model.time() + kChunk);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    steps += model.step() - s0;
  }
  const double simulated_s = bs.iterations() * kChunk;
  bs.counters["wall_s_per_sim_s"] = wall / simulated_s;
  bs.counters["dt_ns"] = 1e9 * simulated_s / static_cast<double>(steps);
  bs.counters["ns_per_step"] = 1e9 * wall / static_cast<double>(steps);
}
BENCHMARK(BM_LumpedSimulatedSecond)
    ->ArgNames({"ehl", "books", "spall", "fast"})
    ->ArgsProduct({{0, 1}, {1, 0}, {1, 0}, {0}})
    ->ArgsProduct({{0, 1}, {1, 0}, {1}, {1}})  // [solver] lumped_step = "fast", spalled
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
