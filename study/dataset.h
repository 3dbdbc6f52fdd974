// Running a sweep into a dataset folder: one HDF5 file per case plus an index
// (docs/DATASET.md is the reference for the layout).
//
//   DIR/sweep.toml          the sweep file the folder was made from (a later run must match it)
//   DIR/case-00000.h5       one simulation per case, written atomically (temp file, rename);
//                           root attributes as `spall simulate` writes them plus case_id,
//                           case_json (id, parameters, labels, overrides), the labels one by one
//                           and wall_seconds
//   DIR/case-00007.failed   a case that threw (the message); skipped on later runs
//   DIR/index.csv, index.json   every case: id, status (ok | failed | pending), file, wall time,
//                           parameters, labels
//
// Resumable: a case is done when its file exists (the rename is the commit), so a run killed at
// any moment and started again runs only the missing cases; temporary files of a killed run are
// removed before their case runs again. A case file made from another scene (an edited sweep)
// is an error, never silently kept.
//
// Distribution: this process runs the cases with index % part_count == part_index, on `workers`
// threads taking cases in index order. MPI ranks and `--shard i/n` both map onto the part; a
// case's file depends only on the sweep (each case runs on one solver thread unless the sweep
// sets solver.threads), so the files are the same for any split.
//
// Ten lines for a library user:
//   const study::Sweep sweep = study::LoadSweep("datasets/sweeps/paper-study.toml");
//   study::DatasetOptions options;
//   options.out_dir = "out/paper";
//   options.workers = 2;
//   const study::DatasetSummary summary = study::RunDataset(sweep, options);
//   std::printf("%s\n", summary.BriefReport().c_str());
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "study/sweep.h"

namespace spallkit::study {

enum class CaseStatus { kPending, kOk, kFailed };
const char* CaseStatusName(CaseStatus status);  // "pending", "ok", "failed"

// Ground truth of a case, from its scene: what a classifier or an identification is scored on.
struct CaseLabels {
  std::string fault_class;  // "healthy" or "roller"
  int defect_count = 0;
  std::string rollers;                               // defective rollers, "0;3" ("" when healthy)
  double width_mm = 0, depth_mm = 0, angle_deg = 0;  // of the first defect (0 when healthy)
  double speed_rpm = 0, radial_load_n = 0, diametral_clearance_mm = 0, mu_dynamic = 0;
  double shaft_hz = 0, f_b_hz = 0, f_c_hz = 0;  // kinematic (f_b = 2 x roller spin)
  std::string fidelity;
  double duration_s = 0, output_rate_hz = 0;

  // Name/value pairs in column order (numbers and strings).
  nlohmann::ordered_json ToJson() const;
};
CaseLabels MakeLabels(const sim::Scene& scene);

struct IndexEntry {
  SweepCase sweep_case;
  CaseStatus status = CaseStatus::kPending;
  std::string file;  // relative to the dataset folder ("" unless ok)
  double wall_seconds = 0;
  nlohmann::ordered_json labels;  // CaseLabels::ToJson() plus post-processing results
  std::string error;              // failed cases
};

struct DatasetProgress {
  int done = 0, total = 0;  // this process's cases, done includes those found on disk
  int failed = 0, running = 0;
  double wall_seconds = 0, eta_seconds = 0;  // eta: NaN until a case has finished in this run
  std::string last_case;
};

struct DatasetOptions {
  std::string out_dir;
  int workers = 1;                     // threads running cases at once (>= 1)
  int part_index = 0, part_count = 1;  // this process runs index % part_count == part_index
  // Rewrite DIR/index.{csv,json} after each case and at the end. With several processes let
  // one of them call WriteIndex once all have finished instead.
  bool write_index = true;
  bool retry_failed = false;                             // run cases with a .failed marker again
  std::function<void(const DatasetProgress&)> progress;  // after each case (from any thread)

  bool Validate(std::string* error) const;
};

struct DatasetSummary {
  int total_cases = 0;      // in the sweep
  int part_cases = 0;       // this process's share
  int already_done = 0;     // found on disk
  int ran = 0, failed = 0;  // this run
  int pending = 0;          // of this process's share, still missing (failed ones included)
  double wall_seconds = 0, case_seconds = 0;  // elapsed; sum of the cases' wall times
  std::string out_dir;
  std::string BriefReport() const;
};

// Runs this process's missing cases. Throws InputError for bad options, a folder holding another
// sweep's cases, or an unwritable folder; a case that fails is recorded (status failed) and
// the others go on.
DatasetSummary RunDataset(const Sweep& sweep, const DatasetOptions& options);

// The index of every case of the sweep, read from the folder's case files and .failed markers.
std::vector<IndexEntry> ScanDataset(const Sweep& sweep, const std::string& out_dir);
// Writes DIR/index.csv and DIR/index.json (atomically) from `entries`.
void WriteIndex(const Sweep& sweep,
                const std::string& out_dir,
                const std::vector<IndexEntry>& entries);

// The case file name of a case ("case-00042.h5").
std::string CaseFileName(const SweepCase& c);

}  // namespace spallkit::study
