// libFuzzer target: the diagnosis (dsp/diagnose.h Diagnose) on arbitrary sample arrays. The first
// 4 bytes choose the sample rate and the shaft speed; the rest are float32 samples (any bit
// pattern: NaN, inf, denormals, constants, spikes). A record that cannot be analysed must be an
// InputError or come back with warnings, never a crash or a non-finite verdict.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/bearing.h"
#include "core/error.h"
#include "core/record.h"
#include "dsp/diagnose.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 4) return 0;
  spallkit::Record record;
  record.sample_rate_hz = 2000.0 * (1 + data[0] % 32);  // 2-64 kHz
  const double shaft_hz = 5.0 + 0.5 * data[1];          // 5-132.5 Hz
  const std::size_t n = (size - 4) / sizeof(float);
  record.samples.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    float v;
    std::memcpy(&v, data + 4 + i * sizeof(float), sizeof v);
    record.samples[i] = v;
  }
  record.source = "fuzz";
  spallkit::dsp::DiagnoseOptions options;
  options.threads = 1;
  try {
    const auto d = spallkit::dsp::Diagnose(
        record, spallkit::CatalogBearing(data[2] % 2 ? "N205EM" : "6205"), shaft_hz, options);
    (void)d.BriefReport();
    (void)d.ToJson();
  } catch (const spallkit::InputError&) {
  }
  return 0;
}
