// Where the tests find the real measured records (CWRU), which are never copied into the
// repository: $SPALLKIT_MEASURED_DIR if set, else shared/data/measured beside the checkout (the
// layout of the development machines and of CI). Tests that need them GTEST_SKIP() when absent.
#pragma once

#include <cstdlib>
#include <string>

namespace spallkit::testing {

inline std::string MeasuredDataDir() {
  if (const char* env = std::getenv("SPALLKIT_MEASURED_DIR")) return env;
  return std::string(SPALLKIT_SOURCE_DIR) + "/../shared/data/measured";
}

}  // namespace spallkit::testing
