// libFuzzer target: the scene parser (sim/bearing/scene.h ParseScene) with --set overrides and the
// scene limits. The input up to the first NUL byte is the TOML text; each following line is one
// "key=value" override. Bad input must be an InputError naming the problem.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"
#include "sim/bearing/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string all(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = all.find('\0');
  const std::string toml = all.substr(0, nul);
  std::vector<std::string> overrides;
  if (nul != std::string::npos) {
    std::size_t start = nul + 1;
    while (start <= all.size() && overrides.size() < 16) {
      const std::size_t end = std::min(all.find('\n', start), all.size());
      overrides.push_back(all.substr(start, end - start));
      start = end + 1;
    }
  }
  try {
    const spallkit::sim::Scene scene = spallkit::sim::ParseScene(toml, "fuzz.toml", overrides);
    // The effective scene must parse back to a scene (it is written into every result file).
    spallkit::sim::ParseScene(scene.effective_toml, "effective.toml");
  } catch (const spallkit::InputError&) {
  }
  return 0;
}
