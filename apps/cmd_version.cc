// spall version: prints the spallkit version (also `spall --version`).
#include <cstdio>

#include "apps/command.h"

namespace {
spallkit::apps::Register reg("version", "Print the spallkit version", [](CLI::App&) {
  return [] {
    std::printf("spallkit %s\n", SPALLKIT_VERSION);
    return 0;
  };
});
}  // namespace
