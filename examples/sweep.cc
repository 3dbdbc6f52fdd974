// A small parameter sweep in memory: a sweep (study/sweep.h, the format of `spall dataset run`)
// expanded into cases, each simulated and diagnosed without files. Here: two spall widths on the
// lumped model at 6000 rpm; `spall dataset run` runs such sweeps in parallel and writes datasets.
//
//   example_sweep [scenes_dir]   (default datasets/scenes)
#include "study/sweep.h"

#include <cstdio>
#include <exception>
#include <string>

#include "core/constants.h"
#include "dsp/diagnose.h"
#include "sim/bearing/record_adapter.h"
#include "sim/bearing/simulation.h"

int main(int argc, char** argv) {
  namespace sim = spallkit::sim;
  const std::string scenes = argc > 1 ? argv[1] : "datasets/scenes";
  const std::string sweep_text = R"(
    [base]
    scene = "paper-verification.toml"
    [base.set]
    "model.fidelity" = "lumped"
    "operation.speed_rpm" = 6000.0
    "run.duration_s" = 0.3
    "friction.mu_static" = 0.1
    "friction.mu_dynamic" = 0.08
    [grid]
    "defects.0.width_mm" = [0.92, 2.27]
  )";
  try {
    const spallkit::study::Sweep sweep = spallkit::study::ParseSweep(sweep_text, "<sweep>", scenes);
    for (const spallkit::study::SweepCase& c : spallkit::study::MakeCases(sweep)) {
      const sim::Scene scene = spallkit::study::CaseScene(sweep, c);
      sim::Simulation simulation(scene, {});
      simulation.Run();
      const double shaft_hz = scene.operation.inner_ring_speed_rad_s / (2.0 * spallkit::kPi);
      const spallkit::dsp::Diagnosis d =
          spallkit::dsp::Diagnose(sim::ToRecord(simulation), scene.geometry.bearing, shaft_hz);
      std::printf("%s width %s mm: %s\n",
                  c.id.c_str(),
                  c.parameters[0].second.dump().c_str(),
                  spallkit::dsp::VerdictName(d.verdict));
    }
  } catch (const std::exception& e) {  // InputError (sweep, scene) or NumericalError (run)
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
