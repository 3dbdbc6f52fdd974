// A diagnosis benchmark: every record of a labelled set (a folder and its manifest) diagnosed with
// its own bearing and speed, and the verdicts tallied against the ground truth (confusion matrix,
// false alarms, per-record evidence, time per record). `spall bench diagnose` prints it.
//
// Manifest (JSON; the format of shared measured-record folders, docs/DIAGNOSIS.md "Benchmark on
// labelled records"): an array of objects, or {"records": [...]}, each with
//   file                  record path, relative to the manifest's folder (CSV or HDF5)
//   fault                 ground truth: normal/healthy, inner_race, outer_race* (any suffix, e.g.
//                         outer_race_6oclock), ball/roller/rolling_element, cage
//   rpm_from_file | rpm   shaft speed (rpm)
//   fs_hz                 optional: sample rate (overrides the file's time column)
//   column                optional: CSV column name or index / HDF5 dataset path
//   bearing               optional: catalogue name (core/bearing.h), or
//   bearing_geometry      {n_rolling_elements, element_diameter_mm, pitch_diameter_mm,
//                          contact_angle_deg}
//
//   auto set = dsp::ReadBenchmarkManifest("data/manifest.json");
//   dsp::BenchmarkResult r = dsp::RunDiagnosisBenchmark(set, {});
//   std::puts(r.BriefReport().c_str());
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/bearing.h"
#include "dsp/diagnose.h"

namespace spallkit::dsp {

// The ground truth of a manifest's "fault": "normal"/"healthy", "inner_race", "outer_race*",
// "ball"/"roller"/"rolling_element", "cage"; nullopt for anything else.
std::optional<Verdict> ParseTruth(const std::string& fault);

struct LabelledRecord {
  std::string path;   // resolved file path
  std::string name;   // the manifest's file entry
  std::string fault;  // the manifest's fault string
  Verdict truth = Verdict::kHealthy;
  BearingGeometry bearing;
  double shaft_hz = 0.0;
  double sample_rate_hz = 0.0;  // 0: from the file
  std::string channel;
};

// Throws InputError naming the manifest, the entry and the key for a missing or bad field.
std::vector<LabelledRecord> ReadBenchmarkManifest(const std::string& manifest_path);

struct BenchmarkRow {
  LabelledRecord record;
  std::optional<Verdict> verdict;  // nullopt: refused (error says why)
  std::string error;
  bool confident = true;  // no record warnings
  double p_value = 1.0;   // of the best-ranked family
  std::string best_family;
  Band band;
  std::optional<double> measured_shaft_hz, measured_hz;  // best family's fundamental
  double kinematic_hz = 0.0;
  double seconds = 0.0;  // wall time of Diagnose (reading excluded)
  double duration_s = 0.0;
  std::string evidence;  // best family's reason line
};

struct BenchmarkResult {
  std::vector<BenchmarkRow> rows;
  int confusion[kVerdicts][kVerdicts] = {};  // [truth][verdict]
  int refused = 0;
  int correct = 0;
  int false_alarms = 0;  // healthy truth, fault verdict
  int healthy_records = 0;
  double total_seconds = 0.0;  // analysis time (wall), every record

  // Seconds of signal of the analysed (not refused) records.
  double SignalSeconds() const;
  std::string BriefReport() const;
  std::string ToJson(int indent = 2) const;
};

// Called after each record: records done, records in all, the record's path.
using BenchmarkProgress = std::function<void(int done, int total, const std::string& path)>;

// Diagnoses each record (a record that cannot be read or analysed is counted as refused, with
// its message; the run continues).
BenchmarkResult RunDiagnosisBenchmark(const std::vector<LabelledRecord>& records,
                                      const DiagnoseOptions& options = {},
                                      const BenchmarkProgress& progress = {});

}  // namespace spallkit::dsp
