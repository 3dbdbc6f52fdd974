// Checks `Identify` against simulated records of known truth (docs/IDENTIFY.md, "Validation on
// simulated records"): each record is a `spall simulate` / `spall dataset run` HDF5 file, whose
// `scene` attribute holds the truth (defective rollers, spall width, speed, load, geometry).
//
//   case file -> channel, first skip_s dropped (start-up) -> diagnosis of the clean record (its
//   band defines the SNR) -> for each SNR: white Gaussian noise at that SNR in the band,
//   diagnosis, identification -> compared with the truth.
//
// A library user checks a folder in a few lines:
//     identify::ValidationOptions o;  o.channel = "/signals/accel_z";  o.snr_db = {20, 10, 0};
//     identify::ValidationReport r = identify::ValidateOnFiles(identify::CaseFiles(dir), o);
//     std::cout << r.Summary();
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "identify/identify.h"

namespace spallkit::identify {

struct ValidationOptions {
  std::string channel = "/signals/accel_y";
  double skip_s = 0.05;  // start-up dropped from every record
  // SNR (dB) of the added noise in the clean record's diagnosis band; +inf: the clean record.
  std::vector<double> snr_db = {std::numeric_limits<double>::infinity()};
  std::uint64_t seed = 1;  // noise: SplitMix64 stream per (seed, record, SNR), Box-Muller
  bool give_load = true;   // pass the scene's radial load to Identify (as `--load-n` does)
  IdentifyOptions identify;
  // Files analysed side by side (threads; each file's records on one thread). The report is the
  // same for any number.
  int workers = 1;
  // Called after each file (all its SNRs), from one worker at a time: files done, files in all,
  // the file's path.
  std::function<void(int done, int total, const std::string& path)> progress;

  bool IsValid(std::string* error) const;
};

// One record at one SNR.
struct ValidatedRecord {
  std::string file;
  double snr_db = 0.0;
  // Truth (from the scene).
  int true_count = 0;
  std::vector<int> true_slots;  // canonical cage slots of the defective rollers
  double true_width_m = 0.0;    // of the first defect (all equal in the validation sweeps)
  double speed_rpm = 0.0, load_n = 0.0;
  double true_delay_s = 0.0;  // geometric entry-exit delay at the identified spin rate
  // The release-landing delay the width relation gives for the true width (what the width fit
  // should find; IdentifyOptions::width_contact_release), 0 when no width fit ran.
  double true_release_delay_s = 0.0;
  // What Identify said.
  std::string verdict;
  bool count_stated = false;
  int count = 0;
  double count_probability = 0.0;  // P(count) as stated
  int count_at_least = 0;          // the lower bound stated (0: none)
  double count_at_least_probability = 0.0;
  std::vector<double> probabilities;
  int count_cage = -1, count_sidebands = -1;  // each feature's most probable K (-1: none)
  double p_cage = 0.0, p_sidebands = 0.0;     // ...and its probability
  double chi2_scale_cage = 0.0, chi2_scale_sidebands = 0.0;
  std::vector<double> log_evidence_cage, log_evidence_sidebands;  // per K, untempered
  // Feature A's hump shape of the most probable K's best configuration (0 when no count fit).
  double hump_exponent = 0.0, hump_edge_gain = 0.0, hump_smear_deg = 0.0;
  bool positions_right = false;     // stated slots equal the truth's (canonical form)
  bool positions_mirrored = false;  // ...equal the truth's mirror image (direction reversed)
  bool width_stated = false;
  double width_m = 0.0, width_low_m = 0.0, width_high_m = 0.0;
  // The width fit whether or not its width was stated (0 when it did not run).
  double delay_s = 0.0, delay_low_s = 0.0, delay_high_s = 0.0, delay_significance = 0.0;
  double pair_power_ratio = 0.0;  // the second event's correlation over the zero-lag power
  // The refit where each defective roller has the load zone to itself (made when the delay lies
  // on another roller's lag; 0 when not made), and whether it gave the width.
  double exclusive_delay_s = 0.0, exclusive_pair_power_ratio = 0.0, exclusive_significance = 0.0;
  bool width_from_exclusive_zone = false;
  std::string reasons;  // "; "-joined
  double cpu_s = 0.0;   // diagnosis + identification, this process's CPU time
  double record_s = 0.0;
};

struct ValidationReport {
  std::vector<ValidatedRecord> records;
  // Per SNR: count confusion (truth 0..3+ x refused / stated 0..max), count and width scores,
  // reliability of the stated probabilities, CPU time per record second.
  std::string Summary() const;
  // One row per record and SNR, with a header line.
  std::string ToCsv() const;
};

// The case files of a dataset folder (case-*.h5, sorted), or InputError when there are none.
std::vector<std::string> CaseFiles(const std::string& folder);

// Throws InputError for invalid options or a file that is not a simulation output.
ValidationReport ValidateOnFiles(const std::vector<std::string>& files,
                                 const ValidationOptions& options);

}  // namespace spallkit::identify
