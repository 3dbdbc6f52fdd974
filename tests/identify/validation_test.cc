// The validation report's summary (identify-check's text output) on hand-made records: the
// per-width line counts each class's spalled records, those without a roller signature, the
// right counts and the widths within 15 %.
#include "identify/validation.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace spallkit::identify {
namespace {

ValidatedRecord Spalled(double width_m, bool signature, bool count_right, double width_read_m) {
  ValidatedRecord r;
  r.snr_db = std::numeric_limits<double>::infinity();
  r.true_count = 1;
  r.true_width_m = width_m;
  r.verdict = signature ? "rolling_element" : "healthy";
  r.count_stated = signature;
  r.count = count_right ? 1 : 2;
  r.width_stated = width_read_m > 0;
  r.width_m = width_read_m;
  return r;
}

TEST(ValidationSummary, CountsEachWidthClassOnItsOwnLine) {
  ValidationReport report;
  report.records.push_back(Spalled(0.6e-3, true, true, 0.0));      // right, no width
  report.records.push_back(Spalled(0.9e-3, false, false, 0.0));    // no signature
  report.records.push_back(Spalled(1.9e-3, true, true, 2.0e-3));   // within 15 %
  report.records.push_back(Spalled(1.6e-3, true, false, 2.0e-3));  // wrong count, +25 %
  ValidatedRecord healthy;                                         // not in the line
  healthy.snr_db = std::numeric_limits<double>::infinity();
  healthy.verdict = "healthy";
  report.records.push_back(healthy);
  const std::string s = report.Summary();
  EXPECT_NE(s.find("[0.5-1.0) mm: 2; 1, 1, 0;"), std::string::npos) << s;
  EXPECT_NE(s.find("[1.5-2.0) mm: 2; 0, 1, 1;"), std::string::npos) << s;
  EXPECT_EQ(s.find("[1.0-1.5)"), std::string::npos) << s;  // no record there: no class
}

}  // namespace
}  // namespace spallkit::identify
