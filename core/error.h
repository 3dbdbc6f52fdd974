// Error types shared by every spallkit library.
//
// Library code reports problems with the user's input (files, keys, options) by throwing
// InputError with a one-line message that names the input and says what was expected,
// e.g. "record.csv:17: non-numeric cell 'abc' in column 2". apps/ turns it into one line on
// stderr and exit code 2. Programmer errors use SPALLKIT_CHECK (always on).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace spallkit {

// Bad user input: a file, a key, an option value. The message is shown to the user as is.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// A numerical failure at run time (instability, non-convergence) that the user can act on.
class NumericalError : public std::runtime_error {
 public:
  explicit NumericalError(const std::string& message) : std::runtime_error(message) {}
};

namespace internal {
[[noreturn]] void CheckFailed(const char* condition,
                              const char* file,
                              int line,
                              const std::string& msg);
}  // namespace internal

}  // namespace spallkit

// Always-on invariant check for programmer errors (like MFEM_VERIFY). Aborts with file:line.
#define SPALLKIT_CHECK(cond, msg)                                                             \
  do {                                                                                        \
    if (!(cond)) {                                                                            \
      std::ostringstream spallkit_check_os_;                                                  \
      spallkit_check_os_ << msg;                                                              \
      ::spallkit::internal::CheckFailed(#cond, __FILE__, __LINE__, spallkit_check_os_.str()); \
    }                                                                                         \
  } while (0)
