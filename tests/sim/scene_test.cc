// Scene files: defaults reproduce the paper, every shipped scene loads, bad scenes give one-line
// errors that name the file, line and key.
#include "sim/bearing/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "core/constants.h"
#include "core/error.h"

namespace spallkit::sim {
namespace {

// Message of the InputError thrown by ParseScene, or "" when it did not throw.
std::string ErrorOf(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    ParseScene(text, "bad.toml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void ExpectOneLineError(const std::string& msg, const std::string& must_contain) {
  EXPECT_NE(msg, "") << "expected an error containing '" << must_contain << "'";
  EXPECT_NE(msg.find(must_contain), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(Scene, EmptySceneGivesThePaperDefaultsInSi) {
  const Scene s = ParseScene("", "empty.toml");
  EXPECT_EQ(s.geometry.bearing.num_elements, 13);
  EXPECT_DOUBLE_EQ(s.geometry.bearing.element_diameter_m, 6.5e-3);
  EXPECT_DOUBLE_EQ(s.geometry.thickness_m, 9e-3);
  EXPECT_DOUBLE_EQ(s.geometry.diametral_clearance_m, 0.02e-3);
  EXPECT_DOUBLE_EQ(s.geometry.pocket_clearance_m, 0.2e-3);
  EXPECT_DOUBLE_EQ(s.geometry.cage_radial_play_m, 0.5e-3);
  EXPECT_DOUBLE_EQ(s.geometry.outer_ring_outer_diameter_m, 52e-3);
  EXPECT_DOUBLE_EQ(s.geometry.inner_ring_bore_diameter_m, 25e-3);
  EXPECT_DOUBLE_EQ(s.materials.cage.youngs_modulus_pa, 100e9);
  EXPECT_DOUBLE_EQ(s.materials.cage.poisson_ratio, 0.36);
  EXPECT_DOUBLE_EQ(s.materials.cage.density_kg_m3, 8920.0);
  EXPECT_DOUBLE_EQ(s.materials.roller.youngs_modulus_pa, 206e9);
  ASSERT_EQ(s.defects.size(), 1u);
  EXPECT_DOUBLE_EQ(s.defects[0].width_m, 1.38e-3);
  EXPECT_DOUBLE_EQ(s.defects[0].depth_m, 0.59e-3);
  EXPECT_DOUBLE_EQ(s.operation.radial_load_n, 10000.0);
  EXPECT_NEAR(s.operation.inner_ring_speed_rad_s, 1200.0 * 2 * kPi / 60.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.operation.ramp_s, 0.005);
  EXPECT_DOUBLE_EQ(s.friction.mu_static, 0.01);
  EXPECT_DOUBLE_EQ(s.friction.mu_dynamic, 0.005);
  EXPECT_DOUBLE_EQ(s.damping.ratio, 0.02);
  EXPECT_DOUBLE_EQ(s.mesh.size_m, 0.25e-3);
  EXPECT_DOUBLE_EQ(s.run.duration_s, 0.2);
  EXPECT_DOUBLE_EQ(s.run.output_rate_hz, 20000.0);
  EXPECT_EQ(s.sensors.size(), 2u);
}

TEST(Scene, EffectiveTomlRoundTripsToTheSameScene) {
  const Scene a = ParseScene("[operation]\nspeed_rpm = 6000\n", "a.toml", {"mesh.size_mm=0.5"});
  EXPECT_NE(a.effective_toml.find("size_mm = 0.5"), std::string::npos) << a.effective_toml;
  EXPECT_NE(a.effective_toml.find("mu_static"), std::string::npos);  // defaults written out
  const Scene b = ParseScene(a.effective_toml, "effective.toml");
  EXPECT_EQ(b.effective_toml, a.effective_toml);
  EXPECT_DOUBLE_EQ(b.mesh.size_m, 0.5e-3);
  EXPECT_DOUBLE_EQ(b.operation.inner_ring_speed_rad_s, a.operation.inner_ring_speed_rad_s);
  EXPECT_EQ(b.defects.size(), 1u);
}

TEST(Scene, EveryShippedSceneLoads) {
  const std::filesystem::path dir = std::filesystem::path(SPALLKIT_SOURCE_DIR) / "datasets/scenes";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW({
      const Scene s = LoadScene(entry.path().string());
      EXPECT_GE(s.defects.size(), 1u);
    });
    ++count;
  }
  EXPECT_GE(count, 10);
}

TEST(Scene, PaperCasesHaveThePaperParameters) {
  const std::string dir = std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/";
  const Scene w = LoadScene(dir + "width-2.27.toml");
  EXPECT_DOUBLE_EQ(w.defects[0].width_m, 2.27e-3);
  EXPECT_NEAR(w.operation.inner_ring_speed_rad_s, 6000.0 * 2 * kPi / 60, 1e-9);
  const Scene d = LoadScene(dir + "depth-0.885.toml");
  EXPECT_DOUBLE_EQ(d.defects[0].depth_m, 0.885e-3);
  const Scene r = LoadScene(dir + "rollers-3.toml");
  EXPECT_EQ(r.defects.size(), 3u);
  EXPECT_NEAR(r.operation.inner_ring_speed_rad_s, 4000.0 * 2 * kPi / 60, 1e-9);
  // The high-speed sweeps run the hybrid model (full-FE rollers lock on their rim facets at the
  // paper's friction below 0.25 mm, and 0.25 mm costs ~40 s per simulated ms); the
  // 1200 rpm verification scene keeps the paper's full FE.
  EXPECT_EQ(w.model.fidelity, Fidelity::kHybrid);
  EXPECT_EQ(d.model.fidelity, Fidelity::kHybrid);
  EXPECT_EQ(r.model.fidelity, Fidelity::kHybrid);
  EXPECT_EQ(LoadScene(dir + "paper-verification.toml").model.fidelity, Fidelity::kFe);
}

TEST(Scene, OverridesSetAnyKeyWithTypeChecking) {
  const std::string dir = std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/";
  const Scene s = LoadScene(dir + "paper-verification.toml",
                            {"mesh.size_mm=0.5",
                             "defects.0.width_mm=2.27",
                             "solver.threads=2",
                             "bearing.catalog=N205EM",
                             "operation.speed_rpm=1800"});
  EXPECT_DOUBLE_EQ(s.mesh.size_m, 0.5e-3);
  EXPECT_DOUBLE_EQ(s.defects[0].width_m, 2.27e-3);
  EXPECT_EQ(s.solver.threads, 2);
  EXPECT_NEAR(s.operation.inner_ring_speed_rad_s, 1800.0 * 2 * kPi / 60, 1e-9);
  // Appending a defect by index == size.
  const Scene t = LoadScene(dir + "paper-verification.toml", {"defects.1.roller=5"});
  ASSERT_EQ(t.defects.size(), 2u);
  EXPECT_EQ(t.defects[1].roller, 5);

  toml::table tbl = toml::parse("[mesh]\nsize_mm = 0.25\n");
  EXPECT_THROW(ApplyOverride(tbl, "mesh.size_mm=\"fine\""), InputError);
  EXPECT_THROW(ApplyOverride(tbl, "mesh.size_mm"), InputError);
  ApplyOverride(tbl, "mesh.size_mm=1");  // integer into a float key
  EXPECT_TRUE(tbl["mesh"]["size_mm"].is_floating_point());
  ExpectOneLineError(ErrorOf("", {"defects.7.width_mm=1"}), "out of range");
  ExpectOneLineError(ErrorOf("", {"run.duration_s=abc"}), "--set run.duration_s");
}

TEST(Scene, BadScenesGiveOneLineErrorsNamingFileLineAndKey) {
  // Unknown key, with the line it is on.
  ExpectOneLineError(ErrorOf("[operation]\nradial_load_n = 1.0\nsped_rpm = 5\n"),
                     "bad.toml:3: unknown key 'operation.sped_rpm'");
  ExpectOneLineError(ErrorOf("[operatoin]\n"), "unknown key 'operatoin'");
  // Wrong type.
  ExpectOneLineError(ErrorOf("[mesh]\nsize_mm = \"fine\"\n"),
                     "bad.toml:2: mesh.size_mm: expected a number, got a string");
  ExpectOneLineError(ErrorOf("[[defects]]\nroller = 1.5\n"),
                     "defects.0.roller: expected an integer");
  // Out of range.
  ExpectOneLineError(ErrorOf("[operation]\nradial_load_n = -5.0\n"),
                     "bad.toml:2: operation.radial_load_n: must be >= 0 (got -5)");
  ExpectOneLineError(ErrorOf("[mesh]\nsize_mm = 0\n"), "mesh.size_mm: must be in (0, 5]");
  ExpectOneLineError(ErrorOf("[materials.cage]\npoisson_ratio = 0.5\n"),
                     "materials.cage.poisson_ratio");
  // Roller index >= count.
  ExpectOneLineError(ErrorOf("[[defects]]\nroller = 13\n"),
                     "bad.toml:2: defects.0.roller: roller index 13 >= roller count 13");
  // Spall wider than the roller.
  ExpectOneLineError(ErrorOf("[[defects]]\nroller = 2\nwidth_mm = 7.0\n"),
                     "bad.toml:3: defects.0.width_mm: spall wider than the roller");
  // Two spalls on one roller, friction order, pockets, outputs, syntax.
  ExpectOneLineError(ErrorOf("[[defects]]\nroller = 2\n[[defects]]\nroller = 2\n"),
                     "defects.1.roller");
  ExpectOneLineError(ErrorOf("[friction]\nmu_static = 0.001\n"), "friction.mu_dynamic");
  ExpectOneLineError(ErrorOf("[bearing]\npocket_clearance_mm = 4.0\n"),
                     "bearing.pocket_clearance_mm");
  ExpectOneLineError(ErrorOf("[bearing]\ncage_radial_play_mm = -0.1\n"),
                     "bearing.cage_radial_play_mm");
  ExpectOneLineError(ErrorOf("[run]\noutputs = [\"movie\"]\n"), "run.outputs: unknown output");
  ExpectOneLineError(ErrorOf("[bearing]\ncatalog = \"X1\"\n"), "bearing.catalog");
  ExpectOneLineError(ErrorOf("[mesh\n"), "bad.toml:1:");
  ExpectOneLineError(ErrorOf("[model]\nfidelity = \"fe\"\n[mesh]\nsize_mm = 2.0\n"),
                     "mesh.contact_size_mm: too coarse");
  ExpectOneLineError(ErrorOf("[solver]\nmax_energy_error_percent = -1\n"),
                     "bad.toml:2: solver.max_energy_error_percent: must be in [0, 100]");
}

TEST(Scene, RingWidthDefaultsToTheN205EMsAndMayNotBeNarrowerThanTheRollers) {
  const Scene s = ParseScene("", "a.toml");
  EXPECT_DOUBLE_EQ(s.geometry.ring_width_m, 15e-3);
  EXPECT_DOUBLE_EQ(s.geometry.thickness_m, 9e-3);
  ExpectOneLineError(ErrorOf("[bearing]\nring_width_mm = 8.0\n"),
                     "bad.toml:2: bearing.ring_width_mm: must be >= thickness_mm (9 mm)");
}

TEST(Scene, SpallLengthDefaultsToThroughLengthAndPartialNeedsTheHybridModel) {
  const Scene s = ParseScene("[bearing]\nthickness_mm = 12.0\n[[defects]]\nroller = 1\n", "a.toml");
  ASSERT_EQ(s.defects.size(), 1u);
  EXPECT_DOUBLE_EQ(s.defects[0].length_m, 12e-3);  // through-length, the paper's 2-D case
  const Scene h = ParseScene(
      "[model]\nfidelity = \"hybrid\"\n[[defects]]\nroller = 1\nlength_mm = 4.5\n", "h.toml");
  EXPECT_DOUBLE_EQ(h.defects[0].length_m, 4.5e-3);
  ExpectOneLineError(
      ErrorOf("[model]\nfidelity = \"fe\"\n[[defects]]\nroller = 1\nlength_mm = 4.5\n"),
      "model.fidelity: defects.0.length_mm is shorter than bearing.thickness_mm");
  // "auto", the default, runs it on a rigid-roller model.
  EXPECT_DOUBLE_EQ(
      ParseScene("[[defects]]\nroller = 1\nlength_mm = 4.5\n", "a.toml").defects[0].length_m,
      4.5e-3);
  ExpectOneLineError(
      ErrorOf("[model]\nfidelity = \"hybrid\"\n[[defects]]\nroller = 1\nlength_mm = 9.5\n"),
      "bad.toml:5: defects.0.length_mm: must be in [0, 9]");
  ExpectOneLineError(
      ErrorOf("[model]\nfidelity = \"hybrid\"\n[[defects]]\nroller = 1\nlength_mm = 0\n"),
      "defects.0.length_mm: must be > 0");
}

// The roller-guided cage's radial play is a geometry key of its own, independent of the pocket
// clearance (Table 1 gives the pocket's width, not its shape).
TEST(Scene, CageRadialPlayIsAKeyOfItsOwn) {
  EXPECT_DOUBLE_EQ(
      ParseScene("[bearing]\npocket_clearance_mm = 0.4\n", "a.toml").geometry.cage_radial_play_m,
      0.5e-3);
  const Scene s = ParseScene("[bearing]\ncage_radial_play_mm = 0.1\n", "b.toml");
  EXPECT_DOUBLE_EQ(s.geometry.cage_radial_play_m, 0.1e-3);
  EXPECT_DOUBLE_EQ(s.geometry.pocket_clearance_m, 0.2e-3);
  EXPECT_NE(s.effective_toml.find("cage_radial_play_mm = 0.1"), std::string::npos)
      << s.effective_toml;
}

// The radial load ramps with the speed unless its own ramp is set (0: a step at t = 0).
TEST(Scene, LoadRampDefaultsToTheSpeedRamp) {
  EXPECT_DOUBLE_EQ(ParseScene("", "default.toml").operation.load_ramp_s, 0.005);
  EXPECT_DOUBLE_EQ(ParseScene("[operation]\nramp_s = 0.002\n", "a.toml").operation.load_ramp_s,
                   0.002);
  const Scene s = ParseScene("[operation]\nload_ramp_s = 0.001\n", "b.toml");
  EXPECT_DOUBLE_EQ(s.operation.load_ramp_s, 0.001);
  EXPECT_DOUBLE_EQ(s.operation.ramp_s, 0.005);
  EXPECT_NE(s.effective_toml.find("load_ramp_s = 0.001"), std::string::npos) << s.effective_toml;
  ExpectOneLineError(ErrorOf("[operation]\nload_ramp_s = -1.0\n"),
                     "bad.toml:2: operation.load_ramp_s: must be >= 0 (got -1)");
}

TEST(Scene, RaceContactIsFacetedCurvedOrSmooth) {
  EXPECT_EQ(ParseScene("", "default.toml").model.race_contact, RaceContact::kSmooth);
  EXPECT_EQ(ParseScene("[model]\nrace_contact = \"faceted\"\n", "f.toml").model.race_contact,
            RaceContact::kFaceted);
  ExpectOneLineError(ErrorOf("[model]\nrace_contact = \"round\"\n"),
                     "model.race_contact: expected \"faceted\", \"curved\" or \"smooth\", got "
                     "\"round\"");
  EXPECT_EQ(ParseScene("[model]\nrace_contact = \"curved\"\n", "c.toml").model.race_contact,
            RaceContact::kCurved);
}

// [model] contact_damping: absent, the models keep their own default; set, a fraction of
// critical in [0, 1]; kept by the effective scene.
TEST(Scene, ContactDampingIsOptionalAndAFractionOfCritical) {
  EXPECT_FALSE(ParseScene("", "default.toml").model.contact_damping.has_value());
  const Scene s = ParseScene("[model]\ncontact_damping = 0.0\n", "d.toml");
  ASSERT_TRUE(s.model.contact_damping.has_value());
  EXPECT_EQ(*s.model.contact_damping, 0.0);
  EXPECT_EQ(ParseScene(s.effective_toml, "again.toml").model.contact_damping, 0.0);
  ExpectOneLineError(ErrorOf("[model]\ncontact_damping = 1.5\n"), "model.contact_damping");
  ExpectOneLineError(ErrorOf("[model]\ncontact_damping = -0.1\n"), "model.contact_damping");
}

// The [model] choices are enums; their names are the scene file's words, and the effective
// scene keeps the words (a re-run reads them back to the same enums).
TEST(Scene, ModelChoicesAreEnumsNamedAsInTheSceneFile) {
  const Scene s = ParseScene(
      "[model]\nfidelity = \"auto\"\nadapter = \"rigid\"\nrace_contact = \"faceted\"\n", "m.toml");
  EXPECT_EQ(s.model.fidelity, Fidelity::kAuto);
  EXPECT_EQ(s.model.adapter, AdapterModel::kRigid);
  EXPECT_EQ(s.model.race_contact, RaceContact::kFaceted);
  const Scene again = ParseScene(s.effective_toml, "effective.toml");
  EXPECT_EQ(again.model.fidelity, Fidelity::kAuto);
  EXPECT_EQ(again.model.adapter, AdapterModel::kRigid);
  EXPECT_EQ(again.model.race_contact, RaceContact::kFaceted);
  EXPECT_EQ(ParseScene("", "d.toml").model.adapter, AdapterModel::kElastic);
  EXPECT_EQ(ParseScene("", "d.toml").model.fidelity, Fidelity::kAuto);

  for (Fidelity f : {Fidelity::kFe, Fidelity::kHybrid, Fidelity::kLumped, Fidelity::kAuto}) {
    Fidelity back = Fidelity::kFe;
    EXPECT_TRUE(ParseFidelity(FidelityName(f), &back)) << FidelityName(f);
    EXPECT_EQ(back, f);
  }
  for (AdapterModel a : {AdapterModel::kElastic, AdapterModel::kRigid}) {
    AdapterModel back = AdapterModel::kElastic;
    EXPECT_TRUE(ParseAdapterModel(AdapterModelName(a), &back));
    EXPECT_EQ(back, a);
  }
  for (RaceContact r : {RaceContact::kFaceted, RaceContact::kCurved, RaceContact::kSmooth}) {
    RaceContact back = RaceContact::kSmooth;
    EXPECT_TRUE(ParseRaceContact(RaceContactName(r), &back));
    EXPECT_EQ(back, r);
  }
  Fidelity f = Fidelity::kFe;
  EXPECT_FALSE(ParseFidelity("FE", &f));
  EXPECT_EQ(f, Fidelity::kFe);
  ExpectOneLineError(ErrorOf("[model]\nfidelity = \"full\"\n"),
                     "model.fidelity: expected \"fe\", \"hybrid\", \"lumped\" or \"auto\", got "
                     "\"full\"");
  ExpectOneLineError(ErrorOf("[model]\nadapter = \"soft\"\n"),
                     "model.adapter: expected \"elastic\" or \"rigid\", got \"soft\"");
  // The lumped model's step rule: "accurate" by default.
  EXPECT_EQ(ParseScene("", "d.toml").solver.lumped_step, LumpedStep::kAccurate);
  EXPECT_EQ(ParseScene("[solver]\nlumped_step = \"fast\"\n", "f.toml").solver.lumped_step,
            LumpedStep::kFast);
  for (LumpedStep l : {LumpedStep::kAccurate, LumpedStep::kFast}) {
    LumpedStep back = LumpedStep::kAccurate;
    EXPECT_TRUE(ParseLumpedStep(LumpedStepName(l), &back));
    EXPECT_EQ(back, l);
  }
  ExpectOneLineError(ErrorOf("[solver]\nlumped_step = \"quick\"\n"),
                     "solver.lumped_step: expected \"accurate\" or \"fast\", got \"quick\"");
}

// [run] outputs: enums in the file's order, the default set when absent, names round-trip.
TEST(Scene, RunOutputsAreEnums) {
  const std::vector<Output> defaults = {Output::kContactForces,
                                        Output::kAcceleration,
                                        Output::kCage,
                                        Output::kRollers,
                                        Output::kEnergy};
  EXPECT_EQ(ParseScene("", "d.toml").outputs, defaults);
  EXPECT_EQ(ParseScene("[run]\noutputs = [\"energy\", \"cage\"]\n", "o.toml").outputs,
            (std::vector<Output>{Output::kEnergy, Output::kCage}));
  EXPECT_TRUE(ParseScene("[run]\noutputs = []\n", "o.toml").outputs.empty());
  const std::vector<std::string> names = KnownOutputs();
  ASSERT_EQ(names.size(), 6u);
  for (const std::string& name : names) {
    Output o = Output::kField;
    EXPECT_TRUE(ParseOutput(name, &o)) << name;
    EXPECT_EQ(OutputName(o), name);
  }
  Output o;
  EXPECT_FALSE(ParseOutput("movie", &o));
}

TEST(Scene, MissingFileIsInputError) {
  EXPECT_THROW(LoadScene("/nonexistent/scene.toml"), InputError);
}

TEST(Scene, EmptyDefectArrayIsAHealthyBearing) {
  const Scene s = ParseScene("defects = []\n", "healthy.toml");
  EXPECT_TRUE(s.defects.empty());
}

}  // namespace
}  // namespace spallkit::sim
