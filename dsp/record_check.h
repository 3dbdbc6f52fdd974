// What a record must be before a diagnosis can be trusted: checked before any spectrum is taken.
//
// Refusals (InputError): an empty record, a non-finite sample, a constant record (no spread: an
// unplugged or saturated channel). Warnings (the record is analysed, but the verdict is flagged
// as not confident): clipping (runs of samples stuck at the record's extreme value) and isolated
// outliers (samples beyond kOutlierSigmas robust standard deviations, e.g. a 1e20 spike or a
// dropout), which dominate a squared envelope and can make or hide a fault comb.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace spallkit::dsp {

struct RecordCheckOptions {
  // A sample this many robust standard deviations (1.4826 x median absolute deviation) from the
  // median is an outlier. Gaussian noise reaches ~6; the measured fault records
  // of docs/DIAGNOSIS.md (34, strongest impacts included) trigger neither warning.
  double outlier_sigmas = 100.0;
  // Clipping: at least this many runs of >= clip_run samples equal to the record's max or min.
  int clip_runs = 2;
  int clip_run = 3;
};

struct RecordCheck {
  double robust_sigma = 0.0;  // 1.4826 x MAD (of every 4th sample when long)
  int outliers = 0;           // samples beyond outlier_sigmas robust sigmas
  long largest_outlier_index = -1;
  int clipped_runs = 0;               // runs of >= clip_run samples at the max or the min
  std::vector<std::string> warnings;  // one line each; empty when the record looks sound
};

// Throws InputError for an empty or constant record or a non-finite sample (naming its index).
RecordCheck CheckRecord(std::span<const double> x, const RecordCheckOptions& options = {});

}  // namespace spallkit::dsp
