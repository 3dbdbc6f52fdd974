#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace spallkit::internal {

void CheckFailed(const char* condition, const char* file, int line, const std::string& msg) {
  std::fprintf(stderr,
               "spallkit: internal check failed at %s:%d: %s (%s)\n",
               file,
               line,
               msg.c_str(),
               condition);
  std::abort();
}

}  // namespace spallkit::internal
