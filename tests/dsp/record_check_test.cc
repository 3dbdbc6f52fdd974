// Records that cannot be analysed honestly: refused (empty, constant, non-finite) or analysed with
// a warning and a verdict flagged not confident (spikes, clipping). Statistics stay finite for
// huge values.
#include "dsp/record_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "core/bearing.h"
#include "core/error.h"
#include "dsp/diagnose.h"
#include "dsp/statistics.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace spallkit::dsp {
namespace {

std::vector<double> Noise(int n, unsigned seed = 3) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = g(rng);
  return x;
}

TEST(RecordCheck, RefusesEmptyConstantAndNonFinite) {
  EXPECT_THROW(CheckRecord(std::vector<double>{}), InputError);
  EXPECT_THROW(CheckRecord(std::vector<double>(1000, 0.0)), InputError);
  EXPECT_THROW(CheckRecord(std::vector<double>(1000, 2.5)), InputError);
  std::vector<double> x = Noise(1000);
  x[7] = std::numeric_limits<double>::quiet_NaN();
  try {
    CheckRecord(x);
    FAIL() << "a NaN sample was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sample 7"), std::string::npos) << e.what();
  }
  x[7] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(CheckRecord(x), InputError);
}

TEST(RecordCheck, GaussianNoiseAndAnImpulsiveFaultHaveNoWarnings) {
  EXPECT_TRUE(CheckRecord(Noise(200000)).warnings.empty());
  spallkit::testing::FaultSignalSpec s;
  s.rate_hz = 107.0;
  s.amplitude = 6.0;  // impulses ~20 noise rms: a strong fault, not a spike
  s.noise_rms = 0.3;
  EXPECT_TRUE(CheckRecord(spallkit::testing::MakeFaultSignal(s)).warnings.empty());
}

TEST(RecordCheck, OneSpikeIsAnOutlierWarning) {
  std::vector<double> x = Noise(100000);
  x[5000] = 1e20;
  const RecordCheck c = CheckRecord(x);
  EXPECT_EQ(c.outliers, 1);
  EXPECT_EQ(c.largest_outlier_index, 5000);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("sample 5000"), std::string::npos) << c.warnings[0];
}

TEST(RecordCheck, ClippedSineIsAClippingWarning) {
  std::vector<double> x(48000);
  for (size_t i = 0; i < x.size(); ++i) x[i] = std::clamp(std::sin(0.01 * i), -0.8, 0.8);
  const RecordCheck c = CheckRecord(x);
  EXPECT_GE(c.clipped_runs, 2);
  ASSERT_FALSE(c.warnings.empty());
  EXPECT_NE(c.warnings.back().find("clipped"), std::string::npos);
  // The unclipped sine touches its extremes in single samples only.
  for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.01 * i);
  EXPECT_EQ(CheckRecord(x).clipped_runs, 0);
}

// The clipping scan skips blocks of samples with no sample at a rail; runs that cross a block
// edge, end the record, or touch both rails are each counted once.
TEST(RecordCheck, ClippedRunsAcrossBlockEdgesAreCountedOnce) {
  std::vector<double> x = Noise(4096, 9);
  for (double& v : x) v = std::clamp(v, -3.0, 3.0) * 0.5;  // within (-1.5, 1.5)
  auto stick = [&](size_t from, size_t count, double rail) {
    for (size_t i = from; i < from + count; ++i) x[i] = rail;
  };
  stick(250, 10, 2.0);     // across the edge at 256
  stick(1000, 3, -2.0);    // exactly clip_run long
  stick(2040, 2, 2.0);     // too short
  stick(3000, 600, -2.0);  // spans whole blocks
  stick(4090, 6, 2.0);     // ends the record
  EXPECT_EQ(CheckRecord(x).clipped_runs, 4);
}

TEST(TimeStatistics, HugeAndTinyValuesStayFinite) {
  std::vector<double> x = Noise(10000);
  x[10] = 1e200;
  const TimeStatistics s = ComputeTimeStatistics(x);
  EXPECT_TRUE(std::isfinite(s.rms));
  EXPECT_TRUE(std::isfinite(s.kurtosis));
  EXPECT_NEAR(s.rms, 1e200 / std::sqrt(10000.0), 1e196);
  EXPECT_NEAR(s.kurtosis, 10000.0, 10.0);  // one sample of N: kurtosis -> N
  for (double& v : x) v = 1e-200 * std::sin(0.1 * (&v - x.data()));
  const TimeStatistics t = ComputeTimeStatistics(x);
  EXPECT_NEAR(t.kurtosis, 1.5, 0.01);  // a sine
  EXPECT_NEAR(t.rms / 1e-200, std::sqrt(0.5), 0.01);
}

Record FaultRecord() {
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = 12000;
  s.duration_s = 2.0;
  s.rate_hz = 107.36 * 0.99;  // 6205 BPFO at 1797 rpm
  s.amplitude = 3.0;
  s.noise_rms = 0.4;
  return spallkit::testing::MakeFaultRecord(s);
}

TEST(DiagnoseBadInput, SpikeGivesAFiniteReportFlaggedNotConfident) {
  Record r = FaultRecord();
  const Diagnosis clean = Diagnose(r, CatalogBearing("6205"), 1797 / 60.0);
  EXPECT_TRUE(clean.warnings.empty());
  EXPECT_TRUE(nlohmann::json::parse(clean.ToJson())["confident"].get<bool>());
  r.samples[1000] = 1e20;
  const Diagnosis d = Diagnose(r, CatalogBearing("6205"), 1797 / 60.0);
  ASSERT_FALSE(d.warnings.empty());
  const auto j = nlohmann::json::parse(d.ToJson());
  EXPECT_FALSE(j["confident"].get<bool>());
  EXPECT_EQ(j["warnings"].size(), d.warnings.size());
  EXPECT_TRUE(std::isfinite(d.statistics.rms));
  EXPECT_TRUE(std::isfinite(d.statistics.kurtosis));
  const std::string report = d.BriefReport();
  EXPECT_NE(report.find("not confident"), std::string::npos);
  EXPECT_EQ(report.find("inf"), std::string::npos) << report;
  EXPECT_EQ(report.find("nan"), std::string::npos) << report;
}

TEST(DiagnoseBadInput, HugeScaleGivesTheSameVerdictAsUnitScale) {
  Record r = FaultRecord();
  const Diagnosis unit = Diagnose(r, CatalogBearing("6205"), 1797 / 60.0);
  for (double& v : r.samples) v *= 1e250;
  const Diagnosis huge = Diagnose(r, CatalogBearing("6205"), 1797 / 60.0);
  EXPECT_EQ(huge.verdict, unit.verdict);
  EXPECT_EQ(huge.verdict, Verdict::kOuterRace);
}

TEST(DiagnoseBadInput, ConstantRecordAndTooManyThreadsAreRefused) {
  Record r = FaultRecord();
  std::fill(r.samples.begin(), r.samples.end(), 0.0);
  EXPECT_THROW(Diagnose(r, CatalogBearing("6205"), 1797 / 60.0), InputError);
  DiagnoseOptions o;
  o.threads = 100000;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("64"), std::string::npos) << error;
}

}  // namespace
}  // namespace spallkit::dsp
