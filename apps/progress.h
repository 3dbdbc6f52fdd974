// Progress of a long command on a terminal: "label: 12/60 records, elapsed 18 s, ETA 72 s (last)"
// rewritten in place on stderr, only when stderr is a terminal (scripts and CI logs get none).
#pragma once

#include <chrono>
#include <string>

namespace spallkit::apps {

// "42 s", "3.5 min", "1.2 h"; "?" when not finite.
std::string FormatDuration(double seconds);

class TerminalProgress {
 public:
  // Off when stderr is not a terminal.
  TerminalProgress(std::string label, std::string unit);
  ~TerminalProgress();  // ends the line if anything was printed
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  void Update(int done, int total, const std::string& last);

 private:
  std::string label_, unit_;
  bool enabled_ = false, printed_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace spallkit::apps
