// sim::ToRecord: a simulation's acceleration as a Record in memory is the record `spall simulate`
// writes (/signals/accel_y and accel_z read back with ReadHdf5Record: same samples, bit for bit,
// same rate and units), and a run without that output or sensor is an InputError.
#include "sim/bearing/record_adapter.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.h"
#include "core/record_io.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"

namespace spallkit::sim {
namespace {

const std::string kScene =
    std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml";

// A coarse FE bearing run for 0.2 ms at 50 kHz (11 samples).
std::vector<std::string> Coarse(std::vector<std::string> extra = {}) {
  std::vector<std::string> sets = {"mesh.size_mm=1.0",
                                   "mesh.contact_size_mm=0.9",
                                   "mesh.adapter_size_mm=2.0",
                                   "defects=[]",
                                   "operation.ramp_s=0.0002",
                                   "run.output_rate_hz=50000",
                                   "run.duration_s=0.0002"};
  sets.insert(sets.end(), extra.begin(), extra.end());
  return sets;
}

TEST(RecordAdapterTest, InMemoryRecordEqualsTheWrittenOne) {
  SimulationOptions options;
  options.output_path = ::testing::TempDir() + "spallkit_record_adapter.h5";
  Simulation simulation(LoadScene(kScene, Coarse()), options);
  ASSERT_TRUE(simulation.Run().completed);

  for (const auto& [axis, name] : {std::pair{AccelerationAxis::kVertical, "accel_y"},
                                   std::pair{AccelerationAxis::kHorizontal, "accel_z"}}) {
    const Record memory = ToRecord(simulation, axis);
    const Record file =
        ReadHdf5Record(options.output_path, {.channel = std::string("/signals/") + name});
    EXPECT_EQ(memory.channel, name);
    EXPECT_EQ(memory.units, "m/s^2");
    EXPECT_EQ(memory.units, file.units);
    EXPECT_EQ(memory.sample_rate_hz, 50000.0);
    EXPECT_EQ(memory.sample_rate_hz, file.sample_rate_hz);
    ASSERT_EQ(memory.samples.size(), 11u);
    EXPECT_EQ(memory.samples, file.samples);
  }
  // By channel index: the default sensors are "top" (y) then "side" (x).
  const Record side = ToRecord(simulation.recorder(), simulation.model(), 1);
  EXPECT_EQ(side.channel, "side_x");
  EXPECT_EQ(side.samples, ToRecord(simulation, AccelerationAxis::kHorizontal).samples);
  EXPECT_THROW(ToRecord(simulation.recorder(), simulation.model(), 2), InputError);
  EXPECT_THROW(ToRecord(simulation.recorder(), simulation.model(), -1), InputError);
}

TEST(RecordAdapterTest, MissingOutputOrSensorIsAnInputError) {
  Simulation no_acceleration(
      LoadScene(kScene, Coarse({"run.duration_s=0.00005", "run.outputs=[\"cage\"]"})), {});
  no_acceleration.Run();
  EXPECT_THROW(ToRecord(no_acceleration), InputError);

  Simulation vertical_only(
      LoadScene(kScene,
                Coarse({"run.duration_s=0.00005",
                        "sensors=[{name=\"top\", x_mm=0.0, y_mm=26.0, directions=[\"y\"]}]"})),
      {});
  vertical_only.Run();
  EXPECT_NO_THROW(ToRecord(vertical_only, AccelerationAxis::kVertical));
  EXPECT_THROW(ToRecord(vertical_only, AccelerationAxis::kHorizontal), InputError);
}

}  // namespace
}  // namespace spallkit::sim
