// EnvelopeAnalyzer::SesPowerFast (single-precision SES power used by the diagnosis' band search)
// against the double-precision SES: same bins, level^2 within a tolerance set by the noise floor,
// independent of the record's scale, the impulse line where it belongs, and bad input rejected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "dsp/envelope.h"
#include "tests/dsp/spectral_test_signals.h"

namespace spallkit::dsp {
namespace {

std::vector<double> Signal(double scale) {
  test_signals::BearingLikeSignal s;
  s.seconds = 2.0;
  std::vector<double> x = test_signals::MakeBearingLikeSignal(s);
  for (double& v : x) v *= scale;
  return x;
}

// Median of v[1..]: the noise floor's level.
double Median(std::vector<double> v) {
  v.erase(v.begin());
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void ExpectMatchesDouble(double scale, const Band& band, double max_alpha_hz) {
  const std::vector<double> x = Signal(scale);
  EnvelopeAnalyzer analyzer(x, 48000);
  const EnvelopeSpectrum ses = analyzer.Compute(band, {.max_alpha_hz = max_alpha_hz});
  int m = 0;
  const std::vector<double> fast = analyzer.SesPowerFast(band, max_alpha_hz, &m);
  ASSERT_EQ(fast.size(), ses.level.size());
  EXPECT_NEAR(m * ses.resolution_hz, ses.envelope_rate_hz, 1e-9 * ses.envelope_rate_hz);
  std::vector<double> exact(ses.level.size());
  for (size_t k = 0; k < exact.size(); ++k) exact[k] = ses.level[k] * ses.level[k];
  const double floor = Median(exact);
  ASSERT_GT(floor, 0.0);
  double worst = 0.0, peak = 0.0;
  for (size_t k = 1; k < exact.size(); ++k) {
    // Relative to the bin itself, or to the floor for bins below it (rounding of float
    // transforms is relative to the signal's RMS, not to each bin).
    worst = std::max(worst, std::abs(fast[k] - exact[k]) / std::max(exact[k], floor));
    peak = std::max(peak, exact[k] / floor);
  }
  EXPECT_LT(worst, 2e-5) << "scale " << scale << ", strongest line " << peak << " x floor";
  EXPECT_GT(peak, 100.0);  // the impulse comb is there, far above the floor
  EXPECT_EQ(fast[0], 0.0);
}

TEST(SesPowerFast, MatchesDoublePrecisionSes) {
  ExpectMatchesDouble(1.0, {7000, 11000}, 1000);
  ExpectMatchesDouble(1.0, {8000, 9500}, 1200);
  ExpectMatchesDouble(1.0, {5000, 13000}, 8000);  // alpha up to the band width
}

TEST(SesPowerFast, IndependentOfTheRecordScale) {
  ExpectMatchesDouble(1e-25, {7000, 11000}, 1000);  // |c|^2 would underflow floats unscaled
  ExpectMatchesDouble(1e22, {7000, 11000}, 1000);
}

TEST(SesPowerFast, LineAtTheImpulseRate) {
  const std::vector<double> x = Signal(1.0);
  EnvelopeAnalyzer analyzer(x, 48000);
  const std::vector<double> p = analyzer.SesPowerFast({7000, 11000}, 1000, nullptr);
  const double df = analyzer.resolution_hz();
  const int lo = static_cast<int>(80 / df), hi = static_cast<int>(140 / df);
  const int best = static_cast<int>(std::max_element(p.begin() + lo, p.begin() + hi) - p.begin());
  EXPECT_NEAR(best * df, 107.3, 2 * df + 0.01 * 107.3);
}

TEST(SesPowerFast, BadInputIsAnInputError) {
  const std::vector<double> x = Signal(1.0);
  EnvelopeAnalyzer analyzer(x, 48000);
  EXPECT_THROW(analyzer.SesPowerFast({7000, 11000}, 0.0, nullptr), InputError);
  EXPECT_THROW(analyzer.SesPowerFast({11000, 7000}, 100.0, nullptr), InputError);
  EXPECT_THROW(analyzer.SesPowerFast({7000, 30000}, 100.0, nullptr), InputError);
}

}  // namespace
}  // namespace spallkit::dsp

namespace spallkit::dsp {
namespace {

// The analyser's finiteness check (one vectorised sum, then a search) names the bad sample
// wherever it is.
TEST(EnvelopeAnalyzerInput, NonFiniteSampleAnywhereIsNamed) {
  for (int at : {0, 3, 64, 998, 999}) {
    std::vector<double> x(1000, 0.25);
    x[at] = at % 2 ? std::nan("") : -HUGE_VAL;
    try {
      EnvelopeAnalyzer analyzer(x, 1000);
      ADD_FAILURE() << "no error at " << at;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("sample " + std::to_string(at) + " "), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace spallkit::dsp
