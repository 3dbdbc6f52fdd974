#include "apps/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace spallkit::apps {

std::string FormatDuration(double s) {
  if (!std::isfinite(s)) return "?";
  char buf[32];
  if (s < 120)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 7200)
    std::snprintf(buf, sizeof buf, "%.1f min", s / 60);
  else
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

TerminalProgress::TerminalProgress(std::string label, std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      enabled_(::isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()) {}

TerminalProgress::~TerminalProgress() {
  if (printed_) std::fprintf(stderr, "\n");
}

void TerminalProgress::Update(int done, int total, const std::string& last) {
  if (!enabled_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = done > 0 ? elapsed / done * (total - done) : NAN;
  std::fprintf(stderr,
               "\r%s: %d/%d %s, elapsed %s, ETA %s (%s)   ",
               label_.c_str(),
               done,
               total,
               unit_.c_str(),
               FormatDuration(elapsed).c_str(),
               FormatDuration(eta).c_str(),
               std::filesystem::path(last).filename().string().c_str());
  std::fflush(stderr);
  printed_ = true;
}

}  // namespace spallkit::apps
