// spall bench fe [--elements N] [--threads T] [--steps S] [--json]: times the explicit engine on
// an inner ring with rollers (sim/solver/engine_benchmark.h) and prints ns per element-cycle
// without and with contact.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/command.h"
#include "core/error.h"
#include "sim/solver/engine_benchmark.h"

namespace {

struct Opts {
  spallkit::sim::solver::EngineBenchmarkOptions bench;
  bool json = false;
};

// Upper bounds, so a typo cannot ask for 1e5 threads (thread creation fails) or a run of days.
constexpr int kMaxThreads = 256;
constexpr int kMaxElements = 5'000'000;
constexpr int kMaxSteps = 100'000;

void CheckLimits(const spallkit::sim::solver::EngineBenchmarkOptions& b) {
  auto in = [](const char* option, int v, int lo, int hi) {
    if (v < lo || v > hi)
      throw spallkit::InputError(std::string(option) + " must be in [" + std::to_string(lo) + ", " +
                                 std::to_string(hi) + "] (got " + std::to_string(v) + ")");
  };
  in("--threads", b.threads, 1, kMaxThreads);
  in("--elements", b.elements, 500, kMaxElements);
  in("--steps", b.steps, 1, kMaxSteps);
}

spallkit::apps::Register reg(
    "bench fe", "Time the explicit FE engine (ns per element-cycle)", [](CLI::App& sub) {
      auto opts = std::make_shared<Opts>();
      sub.add_option(
          "--elements", opts->bench.elements, "Target number of elements (default 40000)");
      sub.add_option("--threads", opts->bench.threads, "OpenMP threads (default 1)");
      sub.add_option("--steps", opts->bench.steps, "Timed steps (default 200)");
      sub.add_flag("--json", opts->json, "Print JSON");
      return [opts] {
        CheckLimits(opts->bench);
        std::string err;
        if (!opts->bench.IsValid(&err)) throw spallkit::InputError(err);
        const auto r = spallkit::sim::solver::RunEngineBenchmark(opts->bench);
        if (opts->json) {
          const nlohmann::json j = {
              {"engine", "fe"},
              {"elements", r.elements},
              {"nodes", r.nodes},
              {"threads", r.threads},
              {"steps", r.steps},
              {"time_step", r.time_step},
              {"ns_per_element_cycle", r.ns_per_element_cycle},
              {"ns_per_element_cycle_with_contact", r.ns_per_element_cycle_with_contact},
              {"cpu_ns_per_element_cycle", r.cpu_ns_per_element_cycle},
              {"cpu_ns_per_element_cycle_with_contact", r.cpu_ns_per_element_cycle_with_contact}};
          std::printf("%s\n", j.dump(2).c_str());
        } else {
          std::printf("fe engine: %d elements, %d nodes, %d thread(s), %d steps, dt %.4g s\n",
                      r.elements,
                      r.nodes,
                      r.threads,
                      r.steps,
                      r.time_step);
          std::printf("  ns_per_element_cycle               %8.2f  (cpu %8.2f)\n",
                      r.ns_per_element_cycle,
                      r.cpu_ns_per_element_cycle);
          std::printf("  ns_per_element_cycle_with_contact  %8.2f  (cpu %8.2f)\n",
                      r.ns_per_element_cycle_with_contact,
                      r.cpu_ns_per_element_cycle_with_contact);
        }
        return 0;
      };
    });

}  // namespace
