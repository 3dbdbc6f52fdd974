// From a simulation's recorder to a Record (core/record.h), the input of the diagnosis, without
// files: the same samples `spall simulate` writes to /signals/accel_y and /signals/accel_z (and
// to the --csv file), in m/s^2 at the scene's [run] output_rate_hz.
//
//   sim::Simulation simulation(scene, {});
//   simulation.Run();
//   Record record = sim::ToRecord(simulation, sim::AccelerationAxis::kVertical);
//   dsp::Diagnosis d = dsp::Diagnose(record, bearing, shaft_hz);
#pragma once

#include "core/record.h"
#include "sim/bearing/model_builder.h"
#include "sim/bearing/recorder.h"
#include "sim/bearing/simulation.h"

namespace spallkit::sim {

// The two public acceleration channels: the first sensor measuring vertically (y; "accel_y") or
// horizontally (x; "accel_z", the paper's LS-DYNA axis name).
enum class AccelerationAxis { kVertical, kHorizontal };

// Channel `channel` of model.sensor_channels() (any sensor and direction). Record::channel is
// "<sensor>_<direction>", Record::source the scene's source. Throws InputError when the recorder
// has no acceleration output or the channel index is out of range.
Record ToRecord(const Recorder& recorder, const BearingModel& model, int channel);

// The first channel along `axis`, named "accel_y" or "accel_z" as in the output files. Throws
// InputError when no sensor measures along that axis or acceleration was not recorded. Call after
// Simulation::Run(): a record of an unfinished run holds the samples recorded so far.
Record ToRecord(const Simulation& simulation, AccelerationAxis axis = AccelerationAxis::kVertical);

}  // namespace spallkit::sim
