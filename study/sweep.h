// Sweep files: a base scene and the parameters to vary, expanded into numbered cases
// (docs/DATASET.md is the reference).
//
//   [base]
//   scene = "../scenes/paper-verification.toml"   # relative to the sweep file's folder
//   [base.set]                                    # overrides, exactly as `spall simulate --set`
//   "model.fidelity" = "hybrid"
//   [grid]                                        # cartesian product of the lists
//   "defects.0.width_mm" = [0.8, 1.2, 1.6]
//   [random]                                      # optional: `cases` draws per grid point
//   cases = 4
//   seed = 1
//   "operation.radial_load_n" = { uniform = [5000.0, 15000.0] }
//   "defects.0.roller" = { choice = [0, 3, 6] }
//   [post]                                        # optional post-processing of each case
//   noise_snr_db = 20.0
//   diagnose = true
//
// Case numbering: grid keys in name order, the first varying slowest; `cases` random draws per
// grid point; case i is "case-<i, 5 digits>". Case i's draws come from its own generator seeded
// with (seed, i), so a case's parameters depend only on the sweep file, never on which worker,
// rank or shard runs it.
//
// Besides scene keys, two sweep keys describe which rollers are defective:
//   "defects.count" = n            n defects (0: healthy): the base scene's defects, truncated, or
//                                  extended with copies of its last defect on the next rollers;
//   "defects.rollers" = [0, 3]     one defect per listed roller (copies as above); [] = healthy.
// They are applied before the other keys, and "defects.<i>.<key>" keys that name a defect the
// case does not have are skipped (a healthy case of a width grid simply has no spall).
// "defects.*.<key>" sets that key on every defect the case has ("defects.*.width_mm").
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sim/bearing/scene.h"

namespace spallkit::study {

// One random parameter: how it is drawn.
struct RandomParameter {
  enum class Kind { kUniform, kLogUniform, kIntegers, kChoice };
  std::string key;
  Kind kind = Kind::kUniform;
  double low = 0, high = 1;             // uniform, log_uniform (low > 0), integers (inclusive)
  std::vector<nlohmann::json> choices;  // choice
};

struct PostOptions {
  // White Gaussian noise added to every acceleration channel at this signal-to-noise ratio (dB,
  // signal RMS over noise RMS); NaN: none. Seeded per case (reproducible).
  double noise_snr_db = std::numeric_limits<double>::quiet_NaN();
  // Run the envelope diagnosis (dsp::Diagnose) on /signals/accel_y and store its verdict.
  bool diagnose = false;
};

struct Sweep {
  std::string path;        // the sweep file (or "<string>")
  std::string text;        // its TOML text
  std::string base_scene;  // resolved path of the base scene
  std::string base_text;   // its TOML text
  std::vector<std::pair<std::string, nlohmann::json>> base_set;
  std::vector<std::pair<std::string, std::vector<nlohmann::json>>> grid;  // name order
  std::vector<RandomParameter> random;                                    // name order
  int random_cases = 1;                                                   // draws per grid point
  unsigned long long seed = 0;
  PostOptions post;

  int num_cases() const;
  // The varied keys (grid then random), i.e. the parameter columns of the index.
  std::vector<std::string> ParameterKeys() const;
};

struct SweepCase {
  int index = 0;
  std::string id;                                                  // "case-00042"
  std::vector<std::pair<std::string, nlohmann::json>> parameters;  // ParameterKeys() order
};

// Reads a sweep file (and its base scene). Throws InputError "<file>: <key>: <expected>".
Sweep LoadSweep(const std::string& path);
// Same from text; relative scene paths are resolved against `base_dir`.
Sweep ParseSweep(const std::string& toml_text,
                 const std::string& source_name,
                 const std::string& base_dir);

std::string CaseId(int index);
// Case `index` (0 <= index < num_cases()).
SweepCase MakeCase(const Sweep& sweep, int index);
std::vector<SweepCase> MakeCases(const Sweep& sweep);

// The `--set` assignments ("key=value") that turn the base scene into the case's scene, in the
// order they are applied (base.set, then the case's parameters).
std::vector<std::string> CaseOverrides(const Sweep& sweep, const SweepCase& c);
// The case's scene (ParseScene of the base with CaseOverrides). Unless base.set names
// solver.threads, a case runs on one thread: a sweep parallelises over cases, and a fixed thread
// count keeps every case file independent of how the sweep is run. Throws InputError naming the
// case.
sim::Scene CaseScene(const Sweep& sweep, const SweepCase& c);

// A JSON value as TOML text for an override ("1.5", "3", "\"hybrid\"", "[0, 3]").
std::string TomlValueText(const nlohmann::json& value);

}  // namespace spallkit::study
