// libFuzzer target: the CSV/text record reader (core/record_io.h ParseCsvRecord) on arbitrary
// bytes. The first byte picks the options (a channel by index or name, a sample rate); the rest is
// the file. Bad input must be an InputError; anything else (a crash, another exception, a
// sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/record_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  spallkit::RecordOptions options;
  const std::uint8_t mode = data[0];
  if (mode & 1) options.channel = std::to_string(mode >> 4);
  if (mode & 2) options.channel = "accel";
  if (mode & 4) options.sample_rate_hz = 1000.0 * ((mode >> 4) + 1);
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const spallkit::Record r = spallkit::ParseCsvRecord(text, "fuzz.csv", options);
    // A record that was accepted must be usable: finite samples, a positive rate.
    if (!(r.sample_rate_hz > 0) || r.samples.size() < 2) __builtin_trap();
  } catch (const spallkit::InputError&) {
  }
  return 0;
}
