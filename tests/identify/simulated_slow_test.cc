// Identification on short records of spallkit's simulator (lumped model, horizontal channel)
// against the truth of their scenes: a spalled roller is counted and placed, a healthy bearing gets
// no count, two spalled rollers never get a wrong count, and the validation harness
// (identify-check) reads a simulated file's truth. About 3 s of CPU per record (simulation
// included), hence the `slow` label.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/bearing.h"
#include "core/constants.h"
#include "dsp/diagnose.h"
#include "identify/identify.h"
#include "identify/validation.h"
#include "sim/bearing/record_adapter.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"

namespace spallkit::identify {
namespace {

constexpr double kLoadN = 10000.0;

// N205EM at 1800 rpm and 10 kN, 0.8 s of which the first 0.05 s (start-up) are dropped; friction
// 0.15 / 0.12 so that the spalls roll through the load zone (datasets/sweeps/identify-tune.toml).
Record Simulate(std::vector<std::string> overrides, double rpm = 1800.0) {
  std::vector<std::string> all = {"model.fidelity=\"lumped\"",
                                  "run.duration_s=0.8",
                                  "run.outputs=[\"acceleration\"]",
                                  "friction.mu_static=0.15",
                                  "friction.mu_dynamic=0.12",
                                  "operation.speed_rpm=" + std::to_string(rpm),
                                  "operation.radial_load_n=10000.0",
                                  "defects.0.width_mm=2.27",
                                  "defects.0.angle_deg=40.0"};
  all.insert(all.end(), overrides.begin(), overrides.end());
  const sim::Scene scene =
      sim::LoadScene(SPALLKIT_SOURCE_DIR "/datasets/scenes/paper-verification.toml", all);
  sim::Simulation simulation(scene, {});
  simulation.Run();
  Record r = sim::ToRecord(simulation, sim::AccelerationAxis::kHorizontal);
  r.samples.erase(r.samples.begin(),
                  r.samples.begin() + static_cast<long>(0.05 * r.sample_rate_hz));
  return r;
}

Identification IdentifyHorizontal(const Record& r, double rpm = 1800.0) {
  const BearingGeometry g = CatalogBearing("N205EM");
  const dsp::Diagnosis d = dsp::Diagnose(r, g, rpm / 60.0);
  IdentifyOptions o;
  o.radial_load_n = kLoadN;
  o.count.sensor_angle_rad = 0.5 * kPi;  // horizontal sensor, vertical load
  return Identify(r, g, rpm / 60.0, d, o);
}

// The true count ranks first; stated (P >= 0.5) only with the right count and position.
TEST(SimulatedRecords, OneSpalledRollerRanksFirst) {
  const Identification id = IdentifyHorizontal(Simulate({}));
  ASSERT_FALSE(id.probabilities.empty()) << id.BriefReport();
  EXPECT_EQ(id.count_fit.MostProbable(), 1) << id.BriefReport();
  if (id.count_identifiable) {
    EXPECT_EQ(id.count, 1);
    EXPECT_EQ(id.positions_deg, (std::vector<double>{0.0}));
  }
  if (id.width_identifiable) {  // stated only with an interval that holds the truth
    EXPECT_LE(id.width_low_m, 2.27e-3) << id.BriefReport();
    EXPECT_GE(id.width_high_m, 2.27e-3) << id.BriefReport();
  }
}

// A 2 mm spall at 1500 rpm (a record of no calibration or validation set): the width is stated,
// within 15 %, its interval holding the truth. The roller is released and lands where the spall's
// gap under the race exceeds its contacts' elastic approach (IdentifyOptions::
// width_contact_release): the delay read as the geometric entry-exit time would give 1.4 mm.
TEST(SimulatedRecords, OneSpalledRollersWidthIsStated) {
  const Identification id = IdentifyHorizontal(
      Simulate({"defects.0.width_mm=2.0", "defects.0.depth_mm=0.8"}, 1500.0), 1500.0);
  std::printf("%s\n", id.BriefReport().c_str());
  ASSERT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_EQ(id.count, 1);
  ASSERT_TRUE(id.width_identifiable) << id.BriefReport();
  EXPECT_NEAR(id.width_m, 2.0e-3, 0.3e-3);
  EXPECT_LE(id.width_low_m, 2.0e-3);
  EXPECT_GE(id.width_high_m, 2.0e-3);
}

TEST(SimulatedRecords, HealthyBearingGetsNoCount) {
  const Identification id = IdentifyHorizontal(Simulate({"defects=[]"}));
  EXPECT_FALSE(id.count_identifiable) << id.BriefReport();
  EXPECT_FALSE(id.width_identifiable);
}

TEST(SimulatedRecords, TwoSpalledRollersGetNoWrongCount) {
  const Identification id = IdentifyHorizontal(Simulate({"defects.1.roller=6",
                                                         "defects.1.width_mm=2.27",
                                                         "defects.1.depth_mm=0.59",
                                                         "defects.1.angle_deg=200.0"}));
  if (id.count_identifiable) {
    EXPECT_EQ(id.count, 2) << id.BriefReport();
  }
  if (id.width_identifiable) {  // stated only with an interval that holds the truth
    EXPECT_LE(id.width_low_m, 2.27e-3) << id.BriefReport();
    EXPECT_GE(id.width_high_m, 2.27e-3) << id.BriefReport();
  }
}

// The validation harness (identify-check) on one simulated file: the truth comes from the file's
// scene, the clean record is identified as Identify alone would, and the CSV row carries the
// fit's delay beside the geometric and the release-landing delay of the true width.
TEST(SimulatedRecords, ValidationHarnessReadsTheTruthAndWritesOneRowPerSnr) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "spallkit_validation_case.h5").string();
  {
    const sim::Scene scene =
        sim::LoadScene(SPALLKIT_SOURCE_DIR "/datasets/scenes/paper-verification.toml",
                       {"model.fidelity=\"lumped\"",
                        "run.duration_s=0.8",
                        "run.outputs=[\"acceleration\"]",
                        "friction.mu_static=0.15",
                        "friction.mu_dynamic=0.12",
                        "operation.speed_rpm=1500.0",
                        "operation.radial_load_n=10000.0",
                        "defects.0.width_mm=2.0",
                        "defects.0.depth_mm=0.8",
                        "defects.0.angle_deg=40.0"});
    sim::SimulationOptions so;
    so.output_path = path;
    sim::Simulation simulation(scene, so);
    ASSERT_TRUE(simulation.Run().completed);
  }
  ValidationOptions o;
  o.channel = "/signals/accel_z";
  o.snr_db = {std::numeric_limits<double>::infinity(), 10.0};
  o.identify.count.sensor_angle_rad = 0.5 * kPi;
  std::vector<std::string> progress;  // "done/total path" per call: once per file, after its SNRs
  o.progress = [&](int done, int total, const std::string& file) {
    progress.push_back(std::to_string(done) + "/" + std::to_string(total) + " " + file);
  };
  const ValidationReport report = ValidateOnFiles({path}, o);
  EXPECT_EQ(progress, (std::vector<std::string>{"1/1 " + path}));
  {
    // Two workers on two files give the report of one worker, in the files' order (the copy's
    // noise has its own seed, so its rows differ from the original's).
    const std::string copy = path + ".copy.h5";
    std::filesystem::copy_file(path, copy, std::filesystem::copy_options::overwrite_existing);
    ValidationOptions one = o;
    one.progress = nullptr;
    one.snr_db = {10.0};
    ValidationOptions two = one;
    two.workers = 2;
    auto csv_without_cpu = [](ValidationReport r) {
      for (auto& rec : r.records) rec.cpu_s = 0.0;
      return r.ToCsv();
    };
    const ValidationReport a = ValidateOnFiles({path, copy}, one);
    const ValidationReport b = ValidateOnFiles({path, copy}, two);
    std::filesystem::remove(copy);
    ASSERT_EQ(b.records.size(), 2u);
    EXPECT_EQ(b.records[0].file, path);
    EXPECT_EQ(b.records[1].file, copy);
    EXPECT_EQ(csv_without_cpu(a), csv_without_cpu(b));
    EXPECT_GT(b.records[0].cpu_s, 0.0);
  }
  std::filesystem::remove(path);
  ASSERT_EQ(report.records.size(), 2u);
  const ValidatedRecord& clean = report.records[0];
  EXPECT_EQ(clean.true_count, 1);
  EXPECT_EQ(clean.true_slots, (std::vector<int>{0}));
  EXPECT_NEAR(clean.true_width_m, 2.0e-3, 1e-9);
  EXPECT_NEAR(clean.speed_rpm, 1500.0, 1e-9);
  EXPECT_NEAR(clean.load_n, 10000.0, 1e-9);
  EXPECT_EQ(clean.verdict, "rolling_element") << clean.reasons;
  ASSERT_TRUE(clean.count_stated) << clean.reasons;
  EXPECT_EQ(clean.count, 1);
  EXPECT_TRUE(clean.positions_right);
  // The roller is released after the leading edge and lands before the trailing one: the delay
  // the relation expects is shorter than the edge-to-edge time, and the fit finds it.
  EXPECT_GT(clean.true_release_delay_s, 0.5 * clean.true_delay_s);
  EXPECT_LT(clean.true_release_delay_s, clean.true_delay_s);
  ASSERT_TRUE(clean.width_stated) << clean.reasons;
  EXPECT_NEAR(clean.delay_s, clean.true_release_delay_s, 0.15 * clean.true_release_delay_s);
  EXPECT_GE(clean.hump_exponent, 0.25);
  EXPECT_LE(clean.hump_exponent, 6.0);
  EXPECT_TRUE(std::isinf(clean.snr_db));
  EXPECT_EQ(report.records[1].snr_db, 10.0);
  // The CSV: a header and one row per record and SNR, each with the header's number of fields
  // (the reasons are one quoted field).
  std::istringstream csv(report.ToCsv());
  std::string header, row;
  ASSERT_TRUE(std::getline(csv, header));
  EXPECT_NE(header.find("true_release_delay_ms,hump_exponent"), std::string::npos) << header;
  auto fields = [](const std::string& line) {
    int n = 1;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      n += c == ',' && !quoted;
    }
    return n;
  };
  int rows = 0;
  while (std::getline(csv, row)) {
    ++rows;
    EXPECT_EQ(fields(row), fields(header)) << row;
  }
  EXPECT_EQ(rows, 2);
}

}  // namespace
}  // namespace spallkit::identify
