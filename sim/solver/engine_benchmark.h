// Timing model for `spall bench fe` and bench/fe_benchmark.cc: an inner ring with rollers
// pressed onto it (1 um interference), about N elements in all, run for a number of steps.
// Reports nanoseconds per element-cycle (wall time / (steps * elements)) for the whole step
// (element forces + gather + central-difference update), without and with the roller/ring
// contact pairs (sim/contact). Double precision, no damping.
#pragma once

#include <memory>
#include <string>

#include "sim/fe/mesh.h"
#include "sim/solver/explicit_solver.h"

namespace spallkit::sim::solver {

struct EngineBenchmarkOptions {
  int elements = 40000;  // target element count (the mesh is within a few % of it)
  int threads = 1;
  int steps = 200;
  int rollers = 8;
  bool energy_terms = true;  // SolverOptions::energy_terms
  bool IsValid(std::string* error) const;
};

struct EngineBenchmarkResult {
  int elements = 0, nodes = 0, threads = 1, steps = 0;
  double ns_per_element_cycle = 0.0;               // no contact
  double ns_per_element_cycle_with_contact = 0.0;  // with one contact pair per roller
  // Process CPU time per element-cycle (all threads summed): on a loaded machine this is the
  // better measure of the work; equal to the wall figure on an idle one with 1 thread.
  double cpu_ns_per_element_cycle = 0.0, cpu_ns_per_element_cycle_with_contact = 0.0;
  double time_step = 0.0;  // s
};

// The ring + rollers mesh (parts "inner_ring", "roller0".."rollerK"), reordered for locality.
fe::Mesh MakeBenchmarkMesh(const EngineBenchmarkOptions& options);

// A solver on that mesh with `with_contact` pairs added (the pairs are owned by the returned
// holder, which keeps them alive as long as the solver).
struct BenchmarkModel {
  fe::Mesh mesh;
  std::unique_ptr<ExplicitSolver> solver;
  std::vector<std::unique_ptr<ForceContributor>> contributors;
};
std::unique_ptr<BenchmarkModel> MakeBenchmarkModel(const EngineBenchmarkOptions& options,
                                                   bool with_contact);

// Builds both models, runs a few warm-up steps, then times options.steps steps of each.
EngineBenchmarkResult RunEngineBenchmark(const EngineBenchmarkOptions& options);

}  // namespace spallkit::sim::solver
