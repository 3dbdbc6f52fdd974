// spall identify: the JSON keys, the text report, and bad input (exit code 2, one line), also of
// spall identify-check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/apps/run_spall.h"

namespace {

using spallkit::testing::RunSpall;

const std::string kSample =
    std::string(SPALLKIT_SOURCE_DIR) + "/datasets/samples/n205em_roller_defect_1200rpm.csv";

TEST(IdentifyCli, JsonHasTheDocumentedKeys) {
  const auto r =
      RunSpall("identify " + kSample + " --bearing N205EM --rpm 1200 --load-n 10000 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* k :
       {"defective_rollers", "width_mm", "identifiable", "diagnosis", "fit", "settings"})
    EXPECT_TRUE(j.contains(k)) << k;
  const auto& dr = j["defective_rollers"];
  for (const char* k : {"count", "probabilities", "positions_deg"})
    EXPECT_TRUE(dr.contains(k)) << k;
  EXPECT_EQ(j["diagnosis"]["verdict"], "rolling_element");
  EXPECT_EQ(dr["count"], 1);  // the sample record has one spalled roller
  EXPECT_FALSE(j["identifiable"]["depth"].get<bool>());
  EXPECT_TRUE(j["identifiable"]["reasons"].is_array());
  double total = 0.0;
  for (const auto& [k, v] : dr["probabilities"].items()) total += v.get<double>();
  EXPECT_NEAR(total, 1.0, 1e-9);
}

// The text report on stdout; --json-out writes beside it the JSON object --json prints.
TEST(IdentifyCli, TextReportAndJsonOut) {
  const std::string json_path =
      (std::filesystem::temp_directory_path() / "spall_identify_json_out.json").string();
  std::filesystem::remove(json_path);
  const auto r =
      RunSpall("identify " + kSample + " --bearing N205EM --rpm 1200 --json-out " + json_path);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("defective rollers: 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("depth: not identifiable"), std::string::npos);
  const auto json = RunSpall("identify " + kSample + " --bearing N205EM --rpm 1200 --json");
  ASSERT_EQ(json.code, 0) << json.err;
  const std::string written = spallkit::testing::ReadTextFile(json_path);
  EXPECT_EQ(written, json.out);
  EXPECT_EQ(nlohmann::json::parse(written)["defective_rollers"]["count"], 1);
}

// A stricter stating threshold than the count's probability refuses the count and says why.
TEST(IdentifyCli, MinCountProbabilityRefusesALessProbableCount) {
  const auto base = RunSpall("identify " + kSample + " --bearing N205EM --rpm 1200 --json");
  ASSERT_EQ(base.code, 0) << base.err;
  const nlohmann::json j0 = nlohmann::json::parse(base.out);
  ASSERT_EQ(j0["defective_rollers"]["count"], 1);
  const double p = j0["defective_rollers"]["probabilities"]["1"].get<double>();
  ASSERT_LT(p, 0.99);
  const auto r = RunSpall("identify " + kSample +
                          " --bearing N205EM --rpm 1200 --json --min-count-probability 0.99");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["defective_rollers"]["count"].is_null());
  EXPECT_FALSE(j["identifiable"]["count"].get<bool>());
  // The lower bound still stands: at least one defective roller, P(K >= 1) = 1 - P(0).
  EXPECT_EQ(j["defective_rollers"]["at_least"]["count"], 1);
  EXPECT_NEAR(j["defective_rollers"]["at_least"]["probability"].get<double>(),
              1.0 - j0["defective_rollers"]["probabilities"]["0"].get<double>(),
              1e-9);
  EXPECT_DOUBLE_EQ(j["settings"]["min_count_bound_probability"].get<double>(), 0.9);
  EXPECT_DOUBLE_EQ(j["settings"]["min_count_probability"].get<double>(), 0.99);
  EXPECT_LT(j0["settings"]["min_count_probability"].get<double>(), 0.99);  // the default
  EXPECT_TRUE(j0["settings"]["width_max_count"].is_number_integer());
  EXPECT_TRUE(j0["settings"]["radial_load_n"].is_null());  // no --load-n
  EXPECT_NE(j["identifiable"]["reasons"].dump().find("count: uncertain"), std::string::npos)
      << j["identifiable"]["reasons"].dump();
  EXPECT_NE(j["identifiable"]["reasons"].dump().find("below the 0.99 a count needs"),
            std::string::npos)
      << j["identifiable"]["reasons"].dump();
}

// The sideband feature's model with one pattern per parity (not the default) and its harmonics
// (--sideband-spin-step) are chosen on the command line and said in the settings; the sample
// record is one roller either way. Each
// statement rule's switch (width rule, cage hump, hump shape, per-count combination, the pair's
// power-ratio bound, the width fit's ring-downs) is said in the settings too.
TEST(IdentifyCli, SidebandPatternAndStatementRulesAreSettings) {
  const auto r = RunSpall("identify " + kSample +
                          " --bearing N205EM --rpm 1200 --json --sideband-pattern-per-parity");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["settings"]["sideband_pattern_per_parity"].get<bool>());
  EXPECT_EQ(j["settings"]["sideband_spin_step"], 1);  // the per-parity model's harmonics
  EXPECT_EQ(j["defective_rollers"]["count"], 1);
  const auto base = RunSpall("identify " + kSample + " --bearing N205EM --rpm 1200 --json");
  ASSERT_EQ(base.code, 0) << base.err;
  EXPECT_FALSE(
      nlohmann::json::parse(base.out)["settings"]["sideband_pattern_per_parity"].get<bool>());
  EXPECT_EQ(nlohmann::json::parse(base.out)["settings"]["sideband_spin_step"], 2);
  EXPECT_EQ(nlohmann::json::parse(base.out)["defective_rollers"]["count"], 1);
  const auto every = RunSpall("identify " + kSample +
                              " --bearing N205EM --rpm 1200 --json --sideband-spin-step 1");
  ASSERT_EQ(every.code, 0) << every.err;
  EXPECT_EQ(nlohmann::json::parse(every.out)["settings"]["sideband_spin_step"], 1);
  EXPECT_EQ(nlohmann::json::parse(every.out)["defective_rollers"]["count"], 1);
  EXPECT_TRUE(
      nlohmann::json::parse(base.out)["settings"]["width_over_uncertain_count"].get<bool>());
  EXPECT_TRUE(nlohmann::json::parse(base.out)["settings"]["max_pair_power_ratio"].is_null());
  EXPECT_FALSE(nlohmann::json::parse(base.out)["settings"]["width_shared_ring_down"].get<bool>());
  const auto shared = RunSpall("identify " + kSample +
                               " --bearing N205EM --rpm 1200 --json --width-shared-ring-down");
  ASSERT_EQ(shared.code, 0) << shared.err;
  EXPECT_TRUE(nlohmann::json::parse(shared.out)["settings"]["width_shared_ring_down"].get<bool>());
  const auto bounded = RunSpall("identify " + kSample +
                                " --bearing N205EM --rpm 1200 --json --max-pair-power-ratio 1");
  ASSERT_EQ(bounded.code, 0) << bounded.err;
  EXPECT_EQ(nlohmann::json::parse(bounded.out)["settings"]["max_pair_power_ratio"], 1.0);
  const auto strict =
      RunSpall("identify " + kSample + " --bearing N205EM --rpm 1200 --json --width-needs-count");
  ASSERT_EQ(strict.code, 0) << strict.err;
  EXPECT_FALSE(
      nlohmann::json::parse(strict.out)["settings"]["width_over_uncertain_count"].get<bool>());
  EXPECT_TRUE(nlohmann::json::parse(base.out)["settings"]["count_needs_cage_hump"].get<bool>());
  const auto loose = RunSpall("identify " + kSample +
                              " --bearing N205EM --rpm 1200 --json --count-without-cage-hump");
  ASSERT_EQ(loose.code, 0) << loose.err;
  EXPECT_FALSE(nlohmann::json::parse(loose.out)["settings"]["count_needs_cage_hump"].get<bool>());
  EXPECT_EQ(nlohmann::json::parse(base.out)["settings"]["min_count_hump_exponent"].get<double>(),
            0.3);
  EXPECT_EQ(
      nlohmann::json::parse(base.out)["settings"]["flat_hump_max_edge_to_centre"].get<double>(),
      2.0);
  EXPECT_EQ(nlohmann::json::parse(base.out)["settings"]["max_count_hump_exponent"].get<double>(),
            5.0);
  const auto extreme = RunSpall("identify " + kSample +
                                " --bearing N205EM --rpm 1200 --json --count-with-extreme-hump");
  ASSERT_EQ(extreme.code, 0) << extreme.err;
  const nlohmann::json je = nlohmann::json::parse(extreme.out);
  EXPECT_EQ(je["settings"]["min_count_hump_exponent"].get<double>(), 0.0);
  EXPECT_EQ(je["settings"]["max_count_hump_exponent"].get<double>(), 6.0);
  EXPECT_FALSE(nlohmann::json::parse(base.out)["settings"]["combine_per_count"].get<bool>());
  const auto per_count =
      RunSpall("identify " + kSample + " --bearing N205EM --rpm 1200 --json --combine-per-count");
  ASSERT_EQ(per_count.code, 0) << per_count.err;
  const nlohmann::json jp = nlohmann::json::parse(per_count.out);
  EXPECT_TRUE(jp["settings"]["combine_per_count"].get<bool>());
  EXPECT_EQ(jp["defective_rollers"]["count"], 1);
}

// A clipped record: the diagnosis warns, and so does the identification's text report (the
// clipping distorts the envelope the count and the width are fitted to).
TEST(IdentifyCli, TextReportCarriesTheRecordWarnings) {
  const std::filesystem::path clipped =
      std::filesystem::temp_directory_path() / "spallkit_identify_clipped.csv";
  {
    std::ifstream in(kSample);
    std::ofstream out(clipped);
    std::string line;
    while (std::getline(in, line)) {
      double t = 0, a = 0;
      if (line.empty() || line[0] == '#' || std::sscanf(line.c_str(), "%lf,%lf", &t, &a) != 2) {
        out << line << "\n";
        continue;
      }
      out << line.substr(0, line.find(',')) << "," << std::clamp(a, -0.5, 0.5) << "\n";
    }
  }
  const auto r = RunSpall("identify " + clipped.string() + " --bearing N205EM --rpm 1200");
  std::filesystem::remove(clipped);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("WARNING (identification not confident)"), std::string::npos) << r.out;
}

TEST(IdentifyCli, BadInputIsOneLineAndCode2) {
  for (const std::string& args :
       {"identify " + kSample + " --bearing N205EM --rpm 0",
        "identify " + kSample + " --bearing N205EM --rpm 1200 --load-n -3",
        "identify " + kSample + " --bearing N205EM --rpm 1200 --min-count-probability 1.5",
        "identify " + kSample + " --bearing N205EM --rpm 1200 --width-max-count 0",
        "identify-check " + std::string(SPALLKIT_SOURCE_DIR) + " --min-count-probability 0",
        std::string("identify /nonexistent.csv --bearing N205EM --rpm 1200"),
        "identify " + kSample + " --bearing NOPE --rpm 1200",
        std::string("identify-check /nonexistent-folder"),
        "identify-check " + std::string(SPALLKIT_SOURCE_DIR) + " --snr-db 10,x",
        "identify-check " + std::string(SPALLKIT_SOURCE_DIR) + " --snr-db 10"}) {
    const auto r = RunSpall(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(r.err.rfind("spall:", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
