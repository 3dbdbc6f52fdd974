#include "sim/verify/verification.h"

namespace spallkit::sim::verify {

std::vector<CaseResult> RunVerification(const std::string& filter) {
  std::vector<CaseResult> results;
  AppendFeCases(&results, filter);
  AppendContactCases(&results, filter);
  return results;
}

}  // namespace spallkit::sim::verify
