#include "sim/bearing/record_adapter.h"

#include <string>

#include "core/error.h"

namespace spallkit::sim {

Record ToRecord(const Recorder& recorder, const BearingModel& model, int channel) {
  const auto& channels = model.sensor_channels();
  if (channel < 0 || channel >= static_cast<int>(channels.size()))
    throw InputError("ToRecord: sensor channel " + std::to_string(channel) + " out of range (" +
                     std::to_string(channels.size()) + " channels)");
  if (!recorder.records_acceleration())
    throw InputError("ToRecord: the run did not record 'acceleration' (scene [run] outputs)");
  Record record;
  record.samples = recorder.Acceleration(channel);
  record.sample_rate_hz = recorder.output_rate_hz();
  record.channel = channels[channel].sensor + "_" + AxisName(channels[channel].direction);
  record.units = "m/s^2";
  record.source = model.scene().source;
  return record;
}

Record ToRecord(const Simulation& simulation, AccelerationAxis axis) {
  const Axis direction = axis == AccelerationAxis::kVertical ? Axis::kY : Axis::kX;
  const auto& channels = simulation.model().sensor_channels();
  for (size_t c = 0; c < channels.size(); ++c) {
    if (channels[c].direction != direction) continue;
    Record record = ToRecord(simulation.recorder(), simulation.model(), static_cast<int>(c));
    record.channel = axis == AccelerationAxis::kVertical ? "accel_y" : "accel_z";
    return record;
  }
  throw InputError(std::string("ToRecord: no sensor measures along ") +
                   (axis == AccelerationAxis::kVertical ? "y (vertical)" : "x (horizontal)"));
}

}  // namespace spallkit::sim
