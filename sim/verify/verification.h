// Verification problems with analytic answers, run by `spall verify` and by the tests.
//
// Each case builds a small model, runs it, and compares one computed quantity with its
// analytic or published reference. Element/solver cases live in fe_cases.cc, contact cases in
// contact_cases.cc.
#pragma once

#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace spallkit::sim::verify {

struct CaseResult {
  std::string name;  // contains one of: patch, rotation, wave, cantilever, hertz, friction, energy
  std::string quantity;  // what is compared, with units, e.g. "wave speed (m/s)"
  double reference = 0.0;
  double computed = 0.0;
  double error =
      0.0;  // relative error |computed - reference| / |reference| (or absolute, see note)
  double tolerance = 0.0;
  bool pass = false;
  std::string note;  // e.g. "absolute error", mesh size
};

// Appends the element / solver cases (patch, rotation, wave, cantilever, ...).
void AppendFeCases(std::vector<CaseResult>* results, const std::string& filter);
// Appends the contact cases (hertz, friction, energy, ...).
void AppendContactCases(std::vector<CaseResult>* results, const std::string& filter);

// Appends the case comparing `computed` with `reference`: relative error, or absolute with
// `absolute` (the note then says so); it passes when the error is finite and within tolerance.
inline void AddCase(std::vector<CaseResult>* results,
                    std::string name,
                    std::string quantity,
                    double reference,
                    double computed,
                    double tolerance,
                    std::string note,
                    bool absolute = false) {
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

// True when a case called `name` is selected by `filter` (empty: every case).
inline bool CaseSelected(std::string_view name, std::string_view filter) {
  return filter.empty() || name.find(filter) != std::string_view::npos;
}

// All cases whose name contains `filter` (empty: all).
std::vector<CaseResult> RunVerification(const std::string& filter = "");

}  // namespace spallkit::sim::verify
