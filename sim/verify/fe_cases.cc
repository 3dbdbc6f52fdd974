#include "sim/verify/verification.h"

namespace spallkit::verify {

// Filled in by the fe engineer; until then it adds no case.
void AppendFeCases(std::vector<CaseResult>*, const std::string&) {}

}  // namespace spallkit::verify
