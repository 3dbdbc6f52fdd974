#include "sim/verify/verification.h"

#include <cmath>
#include <utility>

namespace spallkit::sim::verify {

void AddCase(std::vector<CaseResult>* results,
             std::string name,
             std::string quantity,
             double reference,
             double computed,
             double tolerance,
             std::string note,
             bool absolute) {
  CaseResult r;
  r.name = std::move(name);
  r.quantity = std::move(quantity);
  r.reference = reference;
  r.computed = computed;
  r.error = absolute ? std::abs(computed - reference)
                     : std::abs(computed - reference) / std::abs(reference);
  r.tolerance = tolerance;
  r.pass = std::isfinite(r.error) && r.error <= tolerance;
  r.note = std::move(note) + (absolute ? " (absolute error)" : "");
  results->push_back(std::move(r));
}

std::vector<CaseResult> RunVerification(const std::string& filter) {
  std::vector<CaseResult> results;
  AppendFeCases(&results, filter);
  AppendContactCases(&results, filter);
  return results;
}

}  // namespace spallkit::sim::verify
