// The split comb search (PairScores + CombSearch, what the diagnosis runs per candidate band)
// against its definition: the vectorised pair scores against -ln PairPValue, and a plan made once
// and reused on several spectra against DetectFamily on each.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dsp/detection.h"

namespace spallkit::dsp {
namespace {

// Exponential noise bins on a sloped floor, plus lines at k * f0 (+ sidebands at +/- fs) of
// decreasing height.
std::vector<double> Spectrum(int n, double df, double f0, double fsb, double height, int seed) {
  std::mt19937_64 rng(seed);
  std::exponential_distribution<double> e(1.0);
  std::vector<double> p(n);
  for (int i = 0; i < n; ++i) p[i] = e(rng) * (1.0 + 0.5 * i / n);
  for (int k = 1; k <= 5 && height > 0; ++k)
    for (int m = -1; m <= 1; ++m) {
      const int i = static_cast<int>(std::lround((k * f0 * 1.004 + m * fsb) / df));
      if (i > 0 && i < n) p[i] += height / k / (m == 0 ? 1 : 3);
    }
  return p;
}

TEST(DetectionComb, PairScoresMatchPairPValue) {
  const auto s = NormalizeSpectrum(Spectrum(9000, 0.1, 162.0, 30.0, 400.0, 1), 0.1);
  DetectionOptions o;
  const auto scores = PairScores(s, o);
  ASSERT_EQ(scores.size(), s.z.size() - 1);
  for (size_t i = 0; i + 1 < s.z.size(); ++i) {
    const double z = std::max(s.z[i], s.z[i + 1]);
    const double expected =
        z > 0 ? std::min(-std::log(std::max(s.PairPValue(z), 1e-300)), o.max_line_score) : 0.0;
    ASSERT_NEAR(scores[i], expected, 1e-12 * std::max(1.0, expected)) << "bin " << i;
  }
}

TEST(DetectionComb, PlanReusedAcrossSpectraEqualsDetectFamily) {
  const double shaft = 29.95, df = 0.1;
  const auto fams = MakeFaultFamilies(ComputeFrequencies(CatalogBearing("6205"), shaft));
  DetectionContext ctx;
  ctx.shaft_hz = shaft;
  ctx.center_scale = 1.002;
  ctx.measured_shaft_scale = 1.002;
  ctx.multiplicity = 256;
  DetectionOptions o;
  const int n = 9201;
  std::vector<CombSearch> plans;
  for (const auto& f : fams) plans.emplace_back(f, ctx, o, df, n);
  const auto runs = ScoredPairRuns(plans);
  int detected = 0;
  for (int seed = 0; seed < 6; ++seed) {
    // Inner-race lines with shaft sidebands in half the spectra, noise only in the others.
    const double height = seed % 2 ? 300.0 : 0.0;
    const auto s =
        NormalizeSpectrum(Spectrum(n, df, fams[1].fundamental_hz, shaft, height, seed), df, o);
    const auto scores = PairScores(s, o);
    // Only the pairs the plans read (the diagnosis's way): the same detections.
    const auto run_scores = PairScores(s, o, runs);
    for (size_t f = 0; f < fams.size(); ++f) {
      const FamilyDetection a = plans[f].Detect(s, run_scores);
      const FamilyDetection b = DetectFamily(s, fams[f], ctx, o);
      EXPECT_EQ(plans[f].Detect(s, scores).score, a.score);
      EXPECT_EQ(a.detected, b.detected);
      EXPECT_EQ(a.score, b.score);
      EXPECT_EQ(a.p_value, b.p_value);
      EXPECT_EQ(a.scale, b.scale);
      EXPECT_EQ(a.combinations, b.combinations);
      EXPECT_EQ(a.lines_used, b.lines_used);
      EXPECT_EQ(a.significant_harmonics, b.significant_harmonics);
      ASSERT_EQ(a.lines.size(), b.lines.size());
      for (size_t l = 0; l < a.lines.size(); ++l)
        EXPECT_EQ(a.lines[l].exclusion, b.lines[l].exclusion);
      detected += a.detected;
    }
  }
  EXPECT_GE(detected, 3);  // the inner-race comb in the three spectra that carry it
}

// The pairs the plans read: runs in order, disjoint, covering every line's window and far from
// all of the spectrum; their scores those of the full computation, the rest 0.
TEST(DetectionComb, ScoresOnTheScoredRunsOnly) {
  const double shaft = 29.95, df = 0.1;
  const auto fams = MakeFaultFamilies(ComputeFrequencies(CatalogBearing("6205"), shaft));
  DetectionContext ctx;
  ctx.shaft_hz = shaft;
  DetectionOptions o;
  const int n = 9201;
  std::vector<CombSearch> plans;
  for (const auto& f : fams) plans.emplace_back(f, ctx, o, df, n);
  const auto runs = ScoredPairRuns(plans);
  ASSERT_FALSE(runs.empty());
  std::vector<unsigned char> in_run(n, 0);
  int covered = 0;
  for (size_t r = 0; r < runs.size(); ++r) {
    ASSERT_LT(runs[r].first, runs[r].second);
    if (r > 0) {
      ASSERT_GT(runs[r].first, runs[r - 1].second);  // disjoint and merged
    }
    for (int b = runs[r].first; b < runs[r].second; ++b) in_run[b] = 1;
    covered += runs[r].second - runs[r].first;
  }
  EXPECT_LT(covered, n * 3 / 4);
  // The inner race's first harmonic at the nominal speed lies in a run.
  EXPECT_TRUE(in_run[static_cast<int>(fams[1].fundamental_hz / df)]);
  const auto s = NormalizeSpectrum(Spectrum(n, df, fams[1].fundamental_hz, shaft, 300.0, 4), df, o);
  const auto all = PairScores(s, o);
  const auto some = PairScores(s, o, runs);
  ASSERT_EQ(all.size(), some.size());
  for (size_t b = 0; b < all.size(); ++b) ASSERT_EQ(some[b], in_run[b] ? all[b] : 0.0) << b;
}

// A spectrum of another size is a programming error (SPALLKIT_CHECK), not a wrong answer.
TEST(DetectionCombDeathTest, PlanRejectsAnotherSize) {
  const auto fams = MakeFaultFamilies(ComputeFrequencies(CatalogBearing("6205"), 30.0));
  DetectionContext ctx;
  ctx.shaft_hz = 30.0;
  const CombSearch plan(fams[0], ctx, {}, 0.1, 9201);
  const auto s = NormalizeSpectrum(Spectrum(8000, 0.1, 107.0, 0.0, 0.0, 3), 0.1);
  EXPECT_DEATH(plan.Detect(s, PairScores(s)), "comb search planned");
}

}  // namespace
}  // namespace spallkit::dsp
