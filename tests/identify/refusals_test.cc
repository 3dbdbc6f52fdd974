// What the identification refuses to state: no roller signature, race faults, widths below the
// record's resolution, too few cage revolutions, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "tests/dsp/diagnose_test_signals.h"
#include "tests/identify/identify_test_records.h"

namespace spallkit::identify {
namespace {

using spallkit::testing::IdentifyRecord;
using spallkit::testing::RollerRecordSpec;

void ExpectNothingStated(const Identification& id) {
  EXPECT_FALSE(id.count_identifiable);
  EXPECT_FALSE(id.width_identifiable);
  EXPECT_FALSE(id.depth_identifiable);
  const std::string json = id.ToJson();
  EXPECT_NE(json.find("\"count\": null"), std::string::npos) << json.substr(0, 400);
  EXPECT_NE(json.find("\"width_mm\": null"), std::string::npos);
}

// Identifies a two-roller record of the signal model at 1200 rpm and 10 kN with widths stated
// for up to two rollers, and checks that both rollers are counted.
Identification IdentifyTwoRollers(const Record& r, IdentifyOptions o) {
  o.width_max_count = 2;
  const Identification id = IdentifyRecord(r, 1200, 10000, o);
  EXPECT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_EQ(id.count, 2);
  return id;
}

TEST(Refusals, OuterRaceFaultHasNoRollerCount) {
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = 20000;
  s.duration_s = 1.0;
  s.rate_hz = ComputeFrequencies(CatalogBearing("N205EM"), 20.0).bpfo_hz;
  s.noise_rms = 0.2;
  const Identification id = IdentifyRecord(spallkit::testing::MakeFaultRecord(s), 1200, 10000);
  EXPECT_EQ(id.diagnosis.verdict, dsp::Verdict::kOuterRace);
  EXPECT_FALSE(id.roller_signature);
  ExpectNothingStated(id);
  EXPECT_NE(id.reasons.front().find("race fault"), std::string::npos);
}

TEST(Refusals, NoiseHasNoRollerSignature) {
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = 20000;
  s.duration_s = 1.0;
  const Identification id = IdentifyRecord(spallkit::testing::MakeFaultRecord(s), 1200, 10000);
  EXPECT_EQ(id.diagnosis.verdict, dsp::Verdict::kHealthy);
  ExpectNothingStated(id);
  EXPECT_NE(id.reasons.front().find("no roller signature"), std::string::npos);
}

// A 0.3 mm spall at 1800 rpm: entry and exit 0.17 ms apart, inside the impact's own ring-down in
// any band the record offers; the count is stated, the width is not.
TEST(Refusals, WidthBelowTheResolutionIsNotStated) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1800, 20, {{0, 0.3, 0}}));
  const Identification id = IdentifyRecord(r, 1800, 10000);
  EXPECT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_FALSE(id.width_identifiable) << id.BriefReport();
  EXPECT_EQ(id.width_m, 0.0);
}

// Two rollers with spalls too narrow to give a pair of their own (0.3 mm at 1200 rpm: 0.13 ms),
// in adjacent slots and 25 deg apart in spin phase: each roller's impacts correlate with the
// other's at 1.2 ms, which reads as a 1.4 mm spall. The delay lies on the lag of the two rollers'
// spin phases and no like pair stands out where one roller has the load zone to itself, so no
// width is stated; without the lag rule (cross_lag_half_width_s = 0) the wrong width would be.
TEST(Refusals, DelayOnAnotherRollersImpactsIsNotAWidth) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 20, {{0, 0.3, 0}, {1, 0.3, 25}}, 2));
  IdentifyOptions o = SignalModelOptions();
  const Identification id = IdentifyTwoRollers(r, o);
  EXPECT_FALSE(id.width_identifiable) << id.BriefReport();
  EXPECT_FALSE(id.width_from_exclusive_zone);
  EXPECT_TRUE(spallkit::testing::HasReason(id, "another defective roller's impacts"))
      << id.BriefReport();

  o.cross_lag_half_width_s = 0.0;
  const Identification unguarded = IdentifyTwoRollers(r, o);
  ASSERT_TRUE(unguarded.width_identifiable) << unguarded.BriefReport();
  EXPECT_GT(unguarded.width_m, 1.0e-3);  // the cross correlation read as a wide spall
}

// Two 1.5 mm spalls in slots 0 and 5 whose rollers strike 1.26 ms apart, on their own
// entry-exit delay (1.25 ms at 1200 rpm). The delay lies on the other roller's lag, but the
// autocorrelation where each roller has the load zone to itself (IdentifyOptions::
// width_exclusive_ratio) shows the same pair, so the width is stated, and right; without that
// refit the lag rule refuses it.
TEST(Refusals, PairOnAnotherRollersLagIsConfirmedWhereEachRollerIsAlone) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 20, {{0, 1.5, 0}, {5, 1.5, 26}}, 3));
  IdentifyOptions o = SignalModelOptions();
  const Identification id = IdentifyTwoRollers(r, o);
  ASSERT_TRUE(id.width_identifiable) << id.BriefReport();
  EXPECT_TRUE(id.width_from_exclusive_zone);
  EXPECT_NEAR(id.width_m, 1.5e-3, 0.15 * 1.5e-3);
  double nearest = 1.0;
  for (double lag : id.other_rollers_lags_s)
    nearest = std::min(nearest, std::abs(lag - id.width_fit.best.delay_s));
  EXPECT_LT(nearest, o.cross_lag_half_width_s);  // the delay lies on the other roller's lag

  o.width_exclusive_ratio = 0.0;
  const Identification lag_rule = IdentifyTwoRollers(r, o);
  EXPECT_FALSE(lag_rule.width_identifiable) << lag_rule.BriefReport();
  EXPECT_TRUE(spallkit::testing::HasReason(lag_rule, "another defective roller's impacts"));
}

// Without a stated count the width is still stated when every likely count's configuration gives
// the same pair (IdentifyOptions::width_over_uncertain_count): two 1.5 mm spalls in slots 0 and
// 5, the evidence tempered so that P(2) < 1, and a stating threshold of 1 so that the count is
// refused. The width is then the stated count's, its interval at least as wide; asking the likely
// counts to hold all of the probability refuses it again, and so does a likely count (3, at a
// higher temperature) whose own fit does not resolve the pair, also when 3 is above
// width_max_count; a most probable count above width_max_count refuses it.
TEST(Refusals, WidthWithoutACountWhenEveryLikelyCountGivesTheSamePair) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 20, {{0, 1.5, 0}, {5, 1.5, 26}}, 3));
  IdentifyOptions o = SignalModelOptions();
  o.width_max_count = 3;
  o.count.temperature_cage = o.count.temperature_sidebands = 2.0;
  const Identification stated = IdentifyRecord(r, 1200, 10000, o);
  ASSERT_TRUE(stated.count_identifiable) << stated.BriefReport();
  ASSERT_EQ(stated.count, 2);
  ASSERT_TRUE(stated.width_identifiable) << stated.BriefReport();
  ASSERT_LT(stated.probabilities[2], 1.0) << stated.BriefReport();
  // The text report states the width once and does not also call it not identified.
  EXPECT_EQ(stated.BriefReport().find("width: not identified"), std::string::npos)
      << stated.BriefReport();

  o.min_count_probability = 1.0;
  o.width_over_uncertain_count = false;
  const Identification refused = IdentifyRecord(r, 1200, 10000, o);
  EXPECT_FALSE(refused.count_identifiable);
  EXPECT_FALSE(refused.width_identifiable);
  EXPECT_TRUE(spallkit::testing::HasReason(refused, "needs the count")) << refused.BriefReport();

  o.width_over_uncertain_count = true;
  const Identification over = IdentifyRecord(r, 1200, 10000, o);
  EXPECT_FALSE(over.count_identifiable);
  ASSERT_TRUE(over.width_identifiable) << over.BriefReport();
  EXPECT_EQ(over.width_m, stated.width_m);
  EXPECT_LE(over.width_low_m, stated.width_low_m);
  EXPECT_GE(over.width_high_m, stated.width_high_m);
  ASSERT_FALSE(over.width_counts.empty());
  EXPECT_EQ(over.width_counts.front(), 2);  // the most probable count first
  EXPECT_NE(over.BriefReport().find("the same with each likely count"), std::string::npos);
  EXPECT_EQ(over.BriefReport().find("width: not identified"), std::string::npos)
      << over.BriefReport();
  EXPECT_NE(over.ToJson().find("\"over_counts\""), std::string::npos);

  o.width_count_mass = 1.0;
  const Identification strict = IdentifyRecord(r, 1200, 10000, o);
  EXPECT_FALSE(strict.width_identifiable) << strict.BriefReport();

  o.width_count_mass = IdentifyOptions().width_count_mass;
  o.count.temperature_cage = o.count.temperature_sidebands = 4.0;  // P(3) above 0.05
  const Identification two_counts = IdentifyRecord(r, 1200, 10000, o);
  ASSERT_GE(two_counts.probabilities[3], o.width_count_min_probability) << two_counts.BriefReport();
  EXPECT_FALSE(two_counts.width_identifiable) << two_counts.BriefReport();
  EXPECT_TRUE(spallkit::testing::HasReason(two_counts, "with 3 defective rollers"))
      << two_counts.BriefReport();

  // A likely count above width_max_count is not a refusal by itself: its own fit must agree too
  // (here it does not resolve the pair, as above). The most probable count above it is one.
  o.width_max_count = 2;
  const Identification above_max = IdentifyRecord(r, 1200, 10000, o);
  EXPECT_FALSE(above_max.width_identifiable) << above_max.BriefReport();
  EXPECT_TRUE(spallkit::testing::HasReason(above_max, "with 3 defective rollers"))
      << above_max.BriefReport();
  o.width_max_count = 1;
  const Identification most_probable_above = IdentifyRecord(r, 1200, 10000, o);
  EXPECT_FALSE(most_probable_above.width_identifiable) << most_probable_above.BriefReport();
  EXPECT_TRUE(spallkit::testing::HasReason(most_probable_above, "needs the count"))
      << most_probable_above.BriefReport();
}

// A width beyond the calibration's widest (IdentifyOptions::width_max_diameter_fraction) is not
// stated: a 3.5 mm spall on the 6.5 mm roller (0.54 of it) of the synthetic signal model, whose
// width relation is exact up to the fit's own 0.8, is stated there and refused with the
// simulator calibration's 2.5 / 6.5; the count is stated either way.
TEST(Refusals, WidthBeyondTheCalibrationIsNotStated) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(900, 15, {{0, 3.5, 30}}, 3));
  IdentifyOptions o = SignalModelOptions();
  const Identification within = IdentifyRecord(r, 900, 10000, o);
  ASSERT_TRUE(within.width_identifiable) << within.BriefReport();
  EXPECT_NEAR(within.width_m, 3.5e-3, 0.15 * 3.5e-3);
  o.width_max_diameter_fraction = IdentifyOptions().width_max_diameter_fraction;
  const Identification beyond = IdentifyRecord(r, 900, 10000, o);
  EXPECT_TRUE(beyond.count_identifiable) << beyond.BriefReport();
  EXPECT_FALSE(beyond.width_identifiable);
  EXPECT_EQ(beyond.width_m, 0.0);
  EXPECT_TRUE(spallkit::testing::HasReason(beyond, "wider than the calibration covers"))
      << beyond.BriefReport();
  o.width_max_diameter_fraction = 1.5;
  std::string e;
  EXPECT_FALSE(o.IsValid(&e));
}

// The simulator's width relation (IdentifyOptions::width_contact_release): the roller is released
// sqrt(d delta) past the leading edge and lands sqrt(d delta) before the trailing one, so the same
// measured delay reads w = d sin(asin(w_edges / d) + 2 sqrt(delta / d)), delta the contacts'
// approach at the load-line roller load. Without the radial load the width is refused.
TEST(Refusals, ContactReleaseShiftsTheWidthAndNeedsTheLoad) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(900, 15, {{0, 2.0, 30}}, 3));
  IdentifyOptions o = SignalModelOptions();
  const Identification edges = IdentifyRecord(r, 900, 10000, o);
  ASSERT_TRUE(edges.width_identifiable) << edges.BriefReport();
  o.width_contact_release = true;
  const Identification released = IdentifyRecord(r, 900, 10000, o);
  ASSERT_TRUE(released.width_identifiable) << released.BriefReport();
  const double d = 6.5e-3;
  EXPECT_GT(released.contact_approach_m, 10e-6);  // 2 x Palmgren at 0.7 x 3.6 kN: about 15 um
  EXPECT_LT(released.contact_approach_m, 30e-6);
  EXPECT_NEAR(
      released.width_m,
      d * std::sin(std::asin(edges.width_m / d) + 2.0 * std::sqrt(released.contact_approach_m / d)),
      1e-9);
  // The relation as exported (WidthOfDelay / DelayOfWidth, identify-check's true release delay):
  // the stated width is that of the fitted delay, the inverse gives the delay back, and a spall
  // narrower than 2 sqrt(d delta) is never released (no delay).
  const double delay = released.width_fit.best.delay_s;
  EXPECT_NEAR(WidthOfDelay(delay, d, released, o), released.width_m, 1e-12);
  EXPECT_NEAR(DelayOfWidth(released.width_m, d, released, o), delay, 1e-12);
  EXPECT_EQ(DelayOfWidth(1.9 * std::sqrt(d * released.contact_approach_m), d, released, o), 0.0);
  const BearingGeometry g = CatalogBearing("N205EM");
  const Identification no_load = Identify(r, g, 15.0, dsp::Diagnose(r, g, 15.0), o);
  ASSERT_TRUE(no_load.count_identifiable) << no_load.BriefReport();
  EXPECT_FALSE(no_load.width_identifiable);
  EXPECT_TRUE(spallkit::testing::HasReason(no_load, "needs the radial load"))
      << no_load.BriefReport();
}

// A count fit made by hand for the statement rules (CountRefusal): the combined probabilities and
// each feature's, per K = 0..3, with feature B's lines present.
CountFit HandMadeCountFit(std::vector<double> combined,
                          std::vector<double> cage,
                          std::vector<double> sidebands) {
  CountFit fit;
  fit.sideband_lines = 12;
  fit.probability = std::move(combined);
  fit.probability_cage = std::move(cage);
  fit.probability_sidebands = std::move(sidebands);
  fit.best.resize(fit.probability.size());
  return fit;
}

// The diagnosis itself needs 4 cage revolutions; a stricter requirement refuses the count.
// The count's statement rules on a count fit made by hand (IdentifyOptions::
// count_needs_cage_hump): the combined evidence names two rollers at P 0.95, carried by the
// sideband feature alone while the cage average by itself ranks no roller first (the hybrid's
// 0.46 mm spalls, docs/IDENTIFY.md): refused, and stated when the rule is off or when the cage
// average ranks a roller first.
TEST(Refusals, NoCountWhereTheCageAverageAloneShowsNoHump) {
  CountFit fit =
      HandMadeCountFit({0.02, 0.03, 0.95, 0.0}, {0.45, 0.35, 0.20, 0.0}, {0.0, 0.05, 0.92, 0.03});
  IdentifyOptions o;
  const std::string why = CountRefusal(fit, o);
  EXPECT_NE(why.find("shows no load-zone hump: P(0) = 0.45"), std::string::npos) << why;
  o.count_needs_cage_hump = false;
  EXPECT_EQ(CountRefusal(fit, o), "");
  o.count_needs_cage_hump = true;
  fit.probability_cage = {0.35, 0.45, 0.20, 0.0};
  EXPECT_EQ(CountRefusal(fit, o), "");
  fit.probability = {0.5, 0.3, 0.2, 0.0};  // no hump at all in the combined evidence
  EXPECT_NE(CountRefusal(fit, o).find("not load-modulated"), std::string::npos);
}

// IdentifyOptions::min/max_count_hump_exponent on a count fit made by hand: one roller at P 0.93
// whose hump needed the flattest shape the fit allows (two adjacent rollers' merged humps, as on
// the validation sets) is refused, and so is one whose hump is as narrow as the fit allows (one
// roller's strikes split between humps); with a load-shaped hump, an edge-peaked flat one (the
// hybrid model's single rollers), or with the rules off, it is stated.
TEST(Refusals, NoCountWhereTheHumpIsAsFlatOrAsNarrowAsItsShapeAllows) {
  CountFit fit =
      HandMadeCountFit({0.01, 0.93, 0.06, 0.0}, {0.05, 0.80, 0.15, 0.0}, {0.1, 0.5, 0.3, 0.1});
  fit.best[1].shape.exponent = 0.25;
  fit.best[2].shape.exponent = 1.5;
  IdentifyOptions o;
  const std::string why = CountRefusal(fit, o);
  EXPECT_NE(why.find("hump of 1 defective roller, P = 0.93, is as flat as its shape allows "
                     "(exponent 0.25 < 0.30, edges 1.00 times its centre)"),
            std::string::npos)
      << why;
  fit.best[1].shape.edge_gain = 1.06;  // still flat-topped: edges 1.30 times the centre
  EXPECT_NE(CountRefusal(fit, o).find("edges 1.30 times"), std::string::npos);
  fit.best[1].shape.edge_gain = 7.0;  // edge-peaked
  EXPECT_EQ(CountRefusal(fit, o), "");
  fit.best[1].shape.edge_gain = 0.0;
  fit.best[1].shape.exponent = 0.8;
  EXPECT_EQ(CountRefusal(fit, o), "");
  fit.best[1].shape.exponent = 5.8;
  const std::string narrow = CountRefusal(fit, o);
  EXPECT_NE(narrow.find("is as narrow as its shape allows (exponent 5.80 > 5.00)"),
            std::string::npos)
      << narrow;
  o.max_count_hump_exponent = kHumpMaxExponent;
  EXPECT_EQ(CountRefusal(fit, o), "");
  fit.best[1].shape.exponent = 0.25;
  o.min_count_hump_exponent = 0.0;
  EXPECT_EQ(CountRefusal(fit, o), "");
  o.min_count_hump_exponent = -1.0;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("min_count_hump_exponent"), std::string::npos) << error;
  o = IdentifyOptions();
  o.flat_hump_max_edge_to_centre = 0.5;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("flat_hump_max_edge_to_centre"), std::string::npos) << error;
  o = IdentifyOptions();
  o.max_count_hump_exponent = 0.2;  // below the flat rule's bound
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("max_count_hump_exponent"), std::string::npos) << error;
}

// IdentifyOptions::min_count_bound_probability on a count fit made by hand: two or three rollers,
// neither probable enough to state, give "at least 2" at P(K >= 2) = 0.96; a stricter bound
// probability gives "at least 1"; a fit refused for another reason gives none.
TEST(Refusals, LowerBoundWhereTheCountIsUncertain) {
  CountFit fit =
      HandMadeCountFit({0.0, 0.04, 0.50, 0.46}, {0.05, 0.10, 0.45, 0.40}, {0.0, 0.10, 0.50, 0.40});
  IdentifyOptions o;
  EXPECT_NE(CountRefusal(fit, o).find("uncertain (most probable 2 with P = 0.50"),
            std::string::npos)
      << CountRefusal(fit, o);
  CountBound b = LowerCountBound(fit, o);
  EXPECT_EQ(b.count, 2);
  EXPECT_NEAR(b.probability, 0.96, 1e-12);
  o.min_count_bound_probability = 0.97;
  b = LowerCountBound(fit, o);
  EXPECT_EQ(b.count, 1);
  EXPECT_NEAR(b.probability, 1.0, 1e-12);
  o = IdentifyOptions();
  fit.probability_cage = {0.45, 0.20, 0.20, 0.15};  // the cage average alone ranks 0 first
  EXPECT_EQ(LowerCountBound(fit, o).count, 0);
  o.min_count_bound_probability = 0.5;  // a bound must be more probable than its negation
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("min_count_bound_probability"), std::string::npos) << error;
}

TEST(Refusals, TooFewCageRevolutionsForACount) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 20, {{0}}));  // 8.3 revolutions
  IdentifyOptions o;
  o.min_cage_revolutions = 10;
  const Identification id = IdentifyRecord(r, 1200, 10000, o);
  ASSERT_TRUE(id.roller_signature);
  EXPECT_FALSE(id.count_identifiable);
  EXPECT_NE(id.reasons.front().find("cage revolutions"), std::string::npos);
}

TEST(Refusals, BadInput) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 20, {{0}}));
  const BearingGeometry g = CatalogBearing("N205EM");
  const dsp::Diagnosis d = dsp::Diagnose(r, g, 20.0);
  Record other = r;
  other.samples.resize(r.samples.size() / 2);
  EXPECT_THROW(Identify(other, g, 20.0, d), InputError);
  IdentifyOptions o;
  o.radial_load_n = -5.0;
  std::string e;
  EXPECT_FALSE(o.IsValid(&e));
  EXPECT_THROW(Identify(r, g, 20.0, d, o), InputError);
  SyntheticRecordSpec bad = RollerRecordSpec(1200, 20, {{13}});
  EXPECT_THROW(MakeSyntheticRecord(bad), InputError);
}

}  // namespace
}  // namespace spallkit::identify
