// Simulate a bearing with a spalled roller and diagnose its acceleration in memory: scene ->
// Simulation -> Record (sim/bearing/record_adapter.h) -> Diagnose, no files written.
//
//   example_simulate_and_diagnose [scene.toml]
// Default scene: datasets/scenes/paper-verification.toml, run on the lumped model (rigid rollers
// and rings on a fitted housing, a few seconds here) at 6000 rpm for 0.5 s: 21 cage turns, as the
// diagnosis claims a family only over at least 20 periods of it (DiagnoseOptions::min_periods),
// and a shorter record's cage comb, which shares lines with the roller comb, is not weighed
// against it. The diagnosis calls the roller spall.
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
    const sim::Scene scene = sim::LoadScene(path,
                                            {"model.fidelity=lumped",
                                             "operation.speed_rpm=6000",
                                             "run.duration_s=0.5",
                                             "friction.mu_static=0.1",
                                             "friction.mu_dynamic=0.08"});
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
