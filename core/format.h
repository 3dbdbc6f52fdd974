// One number through a printf conversion ("%.3g", "%.1f %%"), for report and error lines.
#pragma once

#include <cstdio>
#include <string>

namespace spallkit {

inline std::string FormatNumber(const char* printf_format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, value);
  return buf;
}

}  // namespace spallkit
