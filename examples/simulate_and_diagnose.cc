// Simulate a bearing with a spalled roller and diagnose its acceleration in memory: scene ->
// Simulation -> Record (sim/bearing/record_adapter.h) -> Diagnose, no files written.
//
//   example_simulate_and_diagnose [scene.toml]
// Default scene: datasets/scenes/paper-verification.toml, run on the lumped model (rigid rollers
// and rings on a fitted housing) for 1 s at the paper's 1200 rpm with the lubricant traction law,
// about 2 s of wall time. The record holds 8 cage turns, too few to claim a cage comb
// (DiagnoseOptions::min_periods) or to tell a roller comb from one by its rates, which the report
// says; the roller comb's own evidence calls the roller spall.
#include <cstdio>
#include <exception>
#include <string>

#include "core/constants.h"
#include "dsp/diagnose.h"
#include "sim/bearing/record_adapter.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"

int main(int argc, char** argv) {
  namespace sim = spallkit::sim;
  const std::string path = argc > 1 ? argv[1] : "datasets/scenes/paper-verification.toml";
  try {
    const sim::Scene scene =
        sim::LoadScene(path, {"model.fidelity=lumped", "run.duration_s=1", "friction.model=ehl"});
    sim::Simulation simulation(scene, {});  // default options: results stay in memory
    std::printf("%s\n", simulation.Run().BriefReport().c_str());

    const spallkit::Record record = sim::ToRecord(simulation, sim::AccelerationAxis::kVertical);
    const double shaft_hz = scene.operation.inner_ring_speed_rad_s / (2.0 * spallkit::kPi);
    std::printf(
        "%s\n",
        spallkit::dsp::Diagnose(record, scene.geometry.bearing, shaft_hz).BriefReport().c_str());
  } catch (const std::exception& e) {  // InputError (scene, record) or NumericalError (run)
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
