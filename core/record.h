// A single-channel vibration record: what the diagnosis reads (core/record_io.h reads it from
// CSV/HDF5) and what a simulation's recorder produces (sim/bearing/record_adapter.h, ToRecord). It
// lives in core so that the simulator and the DSP layer share it without depending on each other.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace spallkit {

struct Record {
  std::vector<double> samples;  // one channel, uniformly sampled
  double sample_rate_hz = 0;
  std::string channel;  // header name, "column <k>" (0-based data column) or HDF5 dataset path
  std::string units;    // "" when the file does not say
  std::string source;   // the file path; for HDF5 "<file>:<dataset path>"

  double duration_s() const {
    return sample_rate_hz > 0 ? static_cast<double>(samples.size()) / sample_rate_hz : 0.0;
  }
};

// Leaves out the record's first `seconds` (to the nearest sample; e.g. a simulation's start-up).
// False, and the record untouched, when that would leave no sample.
inline bool DropStart(Record* record, double seconds) {
  const double skip = std::round(seconds * record->sample_rate_hz);
  if (!(skip >= 0) || skip >= static_cast<double>(record->samples.size())) return false;
  record->samples.erase(record->samples.begin(),
                        record->samples.begin() + static_cast<std::ptrdiff_t>(skip));
  return true;
}

}  // namespace spallkit
