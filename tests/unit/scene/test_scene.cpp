// Scene parsing and validation, the planner (only the effects the outputs need run), the outputs.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "common/temp_path.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

using namespace fitlib;
using fitlib::core::InputError;

namespace {
const std::string kData = FITLIB_TEST_DATA_DIR "/scenes/";

std::string minimal_text() { return core::read_file(kData + "minimal.toml"); }

// Replaces the first occurrence of `from` in the minimal scene and returns the error key.
InputError parse_error(const std::string& text) {
  try {
    scene::parse_scene(text, "test.toml");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return InputError("none");
}
std::string with(const std::string& from, const std::string& to) {
  std::string t = minimal_text();
  const auto at = t.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return t.replace(at, from.size(), to);
}
}  // namespace

TEST(SceneParse, MinimalSceneDefaults) {
  const auto s = scene::load_scene(kData + "minimal.toml");
  EXPECT_EQ(s.pulleys.size(), 2u);
  EXPECT_EQ(s.section, "cogged-0.500");
  EXPECT_NEAR(s.belt.height_mm, 6.5862, 1e-12);
  EXPECT_NEAR(s.belt.width_mm, 11.1542, 1e-12);
  EXPECT_TRUE(s.outputs.at("load_history"));  // no [outputs]: the load history
  EXPECT_TRUE(s.effects.empty());             // no [effects]: none of the refinements
  EXPECT_EQ(*s.c_N, 44000.0);
}

TEST(SceneParse, UnknownKeysAndWrongUnitsNameTheKeyAndLine) {
  auto e = parse_error(with("center_distance_mm = 300", "center_distance_m = 0.3"));
  EXPECT_EQ(e.key(), "drive.center_distance_m");
  EXPECT_EQ(e.line(), 3);
  e = parse_error(with("torque_Nm = 15", "torque_Nm = \"15 Nm\""));
  EXPECT_EQ(e.key(), "drive.torque_Nm");
  e = parse_error(with("friction = 0.5", "friction = 0.5\nfrictoin = 0.3"));
  EXPECT_EQ(e.key(), "conditions.frictoin");
  // An unknown key says what the table takes (a pulley's position is center_mm, not x_mm).
  e = parse_error(with("role = \"driven\"", "role = \"driven\", x_mm = 350"));
  EXPECT_EQ(e.key(), "drive.pulleys[1].x_mm");
  EXPECT_NE(std::string(e.what()).find("this table takes name, pitch_diameter_mm, role, speed_rpm, torque_Nm, "
                                       "center_mm"), std::string::npos) << e.what();
  e = parse_error(with("role = \"driven\"", "role = \"follower\""));
  EXPECT_EQ(e.key(), "drive.pulleys[1].role");
  e = parse_error(with("pitch_diameter_mm = 100, role = \"driver\"", "pitch_diameter_mm = -100, role = \"driver\""));
  EXPECT_EQ(e.key(), "drive.pulleys[0].pitch_diameter_mm");
  e = parse_error(with("slack_tension_N = 300", "slack_tension_N = -5"));
  EXPECT_EQ(e.key(), "drive.slack_tension_N");
  e = parse_error(with("slack_tension_N = 300", "slack_tension_N = 300\ninitial_tension_N = 400"));
  EXPECT_EQ(e.key(), "drive.initial_tension_N");
  e = parse_error(minimal_text() + "[effects]\nwarp_drive = true\n");
  EXPECT_EQ(e.key(), "effects.warp_drive");
  e = parse_error(minimal_text() + "[outputs]\nlife = \"yes\"\n");
  EXPECT_EQ(e.key(), "outputs.life");
  e = parse_error("[drive\n");
  EXPECT_EQ(e.line(), 1);
}

// A cog that does not fit says by how much, in the section's own numbers, and a sharp corner
// (a round of 0 mm: a stress singularity the design points do not see) is refused with that reason.
TEST(SceneParse, ACogThatDoesNotFitSaysByHowMuchAndASharpCornerIsRefused) {
  const std::string segment = "[segment]\nstrain = 0.01\n";
  const auto belt = [&](const std::string& keys) { return with("[belt.stiffness]", "[belt]\n" + keys + "\n[belt.stiffness]") + segment; };
  // Defaults: land half-width 1.75 mm, depth 2.5 mm, flank 20 deg: the tip corner at
  // 1.75 + 2.5 tan 20° = 2.66 mm, past half of a 4 mm pitch before its round.
  auto e = parse_error(belt("cog_pitch_mm = 4"));
  EXPECT_EQ(e.key(), "belt.cog_tip_radius_mm");
  EXPECT_NE(std::string(e.what()).find("corner lies 2.66 mm from the gap centre"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("past half the pitch (2 mm)"), std::string::npos) << e.what();
  e = parse_error(belt("cog_root_fillet_mm = 3"));
  EXPECT_EQ(e.key(), "belt.cog_root_fillet_mm");
  EXPECT_NE(std::string(e.what()).find("half-width (cog_land_half_width_mm) is 1.75 mm"), std::string::npos) << e.what();
  e = parse_error(belt("cog_depth_mm = 0.05"));
  EXPECT_EQ(e.key(), "belt.cog_depth_mm");
  EXPECT_NE(std::string(e.what()).find("cogged sections only"), std::string::npos) << e.what();
  for (const char* key : {"cog_root_fillet_mm", "cog_tip_radius_mm"}) {
    e = parse_error(belt(std::string(key) + " = 0"));
    EXPECT_EQ(e.key(), std::string("belt.") + key);
    EXPECT_NE(std::string(e.what()).find("sharp corner"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parse_error(belt("cog_root_fillet_mm = -1")).key(), "belt.cog_root_fillet_mm");
  EXPECT_NO_THROW(scene::parse_scene(belt("cog_pitch_mm = 12\ncog_root_fillet_mm = 1"), "ok.toml"));
}

// A card or fatigue card the scene names but that is not there fails at its key and line, with the
// path that was tried (the scene's folder), not later in the card reader with the bare file name.
TEST(SceneParse, MissingCardFilesNameTheKeyLineAndThePathTried) {
  const std::string scene = kData + "minimal.toml";
  for (const auto& [table, key] : {std::pair<std::string, std::string>{"belt.materials", "cushion"}, {"life", "card"}}) {
    try {
      scene::parse_scene(minimal_text() + "[" + table + "]\n" + key + " = \"no-such-card.json\"\n", scene);
      ADD_FAILURE() << table << "." << key << ": no error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), table + "." + key);
      EXPECT_GT(e.line(), 1);
      const std::string tried = std::filesystem::path(kData + "no-such-card.json").lexically_normal().string();
      EXPECT_NE(std::string(e.what()).find("no card file " + tried), std::string::npos) << e.what();
    }
  }
  // A card that is there parses (the path resolved against the scene's folder).
  const auto s = scene::parse_scene(minimal_text() + "[belt.materials]\ncushion = \"minimal.toml\"\n", scene);
  EXPECT_EQ(s.materials.at("cushion"), std::filesystem::path(kData + "minimal.toml").lexically_normal().string());
}

TEST(SceneParse, ImpossibleGeometryIsAnInputError) {
  const auto s = scene::parse_scene(with("center_distance_mm = 300", "center_distance_mm = 90"), "x.toml");
  try {
    scene::run_scene(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "drive.center_distance_mm");
    EXPECT_NE(std::string(e.what()).find("overlap"), std::string::npos);
  }
}

// [belt] length_mm is checked against the drive's cord-line length (2·300 + π·100 = 914.16 mm),
// never silently ignored: within 1 % it runs, beyond it is bad input naming the key.
TEST(SceneParse, GivenBeltLengthMustAgreeWithTheDrivesGeometry) {
  const std::string belt = "[belt.stiffness]";
  EXPECT_NO_THROW(scene::run_scene(scene::parse_scene(with(belt, "[belt]\nlength_mm = 920\n" + belt), "x.toml")));
  const auto s = scene::parse_scene(with(belt, "[belt]\nlength_mm = 1000\n" + belt), "x.toml");
  try {
    scene::run_scene(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "belt.length_mm");
    EXPECT_EQ(e.file(), "x.toml");
    EXPECT_NE(std::string(e.what()).find("914.159"), std::string::npos) << e.what();
  }
}

TEST(Planner, RunsOnlyWhatTheOutputsNeed) {
  auto s = scene::load_scene(kData + "minimal.toml");
  auto plan = scene::make_plan(s);
  EXPECT_TRUE(plan.will_run("contact_arcs"));
  for (const char* off : {"bending_zones", "inertia", "full_ode", "driver_exit_ramp", "strain_accumulation", "cvt_thrust"})
    EXPECT_FALSE(plan.will_run(off)) << off;
  const auto r = scene::run_scene(s);
  for (const auto& e : r.plan.effects) EXPECT_EQ(e.ran, plan.will_run(e.name)) << e.name;
  EXPECT_EQ(r.cycle->centrifugal_tension_N, 0.0);  // inertia not asked for
  // Nothing requested: nothing runs.
  s.outputs = {{"load_history", false}};
  s.effects = {{"inertia", true}};
  const auto none = scene::run_scene(s);
  for (const auto& e : none.plan.effects) EXPECT_FALSE(e.ran) << e.name;
  EXPECT_FALSE(none.cycle.has_value());
}

TEST(Planner, FullSceneRunsEveryAvailableEffectWithLifeAtTheBeamLevel) {
  const auto s = scene::load_scene(kData + "full.toml");
  const auto r = scene::run_scene(s);
  for (const char* on : {"stiffness", "drive", "contact_arcs", "bending_zones", "inertia", "full_ode",
                         "driver_exit_ramp", "viscoelastic_tension", "strain_accumulation", "cvt_thrust",
                         "beam_stresses", "fatigue"}) {
    auto it = std::find_if(r.plan.effects.begin(), r.plan.effects.end(), [&](const auto& e) { return e.name == on; });
    ASSERT_NE(it, r.plan.effects.end()) << on;
    EXPECT_TRUE(it->ran) << on;
    EXPECT_GE(it->wall_s, 0.0);
  }
  EXPECT_TRUE(r.plan.unavailable_outputs.empty());
  ASSERT_TRUE(r.life.has_value());
  EXPECT_EQ(r.life->plan.fidelity, core::Fidelity::beam);
  auto fe = std::find_if(r.plan.effects.begin(), r.plan.effects.end(), [](const auto& e) { return e.name == "segment_fe"; });
  ASSERT_NE(fe, r.plan.effects.end());
  EXPECT_FALSE(fe->ran);
  EXPECT_EQ(fe->status, scene::EffectStatus::not_requested);
  // Power → torque: 4 kW at 3000 rpm = 12.73 N·m on R = 50 mm → ΔF = 254.6 N.
  const auto& F = r.drive->span_tension_N;
  EXPECT_NEAR(F[1] - F[0], 4000.0 / (3000 * 2 * M_PI / 60) * 1000 / 50, 1e-9);
  EXPECT_NEAR(F[1] + F[0], 1000.0, 1e-9);
  // Accumulation map and its critical area.
  ASSERT_TRUE(r.accumulation.has_value());
  EXPECT_EQ(r.accumulation->omega_rad_s.size(), 30u);
  EXPECT_NEAR(r.accumulation->kappa, 500.0 / 50.0, 1e-12);
  const auto j = scene::summary_json(s, r);
  EXPECT_TRUE(j.contains("cvt_thrust"));
  EXPECT_GT(j["viscoelastic_tension"]["driver"]["main_sliding_deg"].get<double>(), 0.0);
  EXPECT_GT(j["cvt_thrust"]["driver_axial_thrust_N"].get<double>(), 0.0);
  EXPECT_TRUE(j["load_cycle"]["pulleys"][0]["sliding_ode_deg"].get<double>() > 0.0);
}

TEST(Planner, ThreePulleyDrive) {
  const auto s = scene::load_scene(kData + "three_pulley.toml");
  const auto r = scene::run_scene(s);
  ASSERT_EQ(r.cycle->pulleys.size(), 3u);
  double wraps = 0;
  for (const auto& p : r.cycle->pulleys) wraps += p.wrap_rad;
  EXPECT_NEAR(wraps, 2 * M_PI, 1e-9);
  // The pump takes 20 N·m on R = 80 mm = 250 N; the driver supplies 11.25 N·m / 45 mm = 250 N.
  const auto& F = r.drive->span_tension_N;
  EXPECT_NEAR(F[1] - F[0], 250.0, 1e-9);
  EXPECT_NEAR(F[2], F[1], 1e-12);  // the idler passes the tension on
}

TEST(Outputs, WritesCsvAndJsonAtomically) {
  const auto s = scene::load_scene(kData + "full.toml");
  const auto r = scene::run_scene(s);
  const auto dir = std::filesystem::temp_directory_path() / ("fitlib_test_scene_out-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const auto files = scene::write_outputs(s, r, dir.string());
  EXPECT_EQ(files.size(), 5u);  // load history, accumulation, stress history, life, summary
  const std::string csv = core::read_file((dir / "load_history.csv").string());
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "s_mm,t_s,pulley,zone,F_N,K_1_per_mm,p_MPa,gamma_deg,sliding_velocity_mm_s,friction_used");
  EXPECT_EQ(csv.find("nan"), std::string::npos);
  EXPECT_EQ(csv.find("inf"), std::string::npos);
  const auto j = nlohmann::json::parse(core::read_file((dir / "summary.json").string()));
  EXPECT_TRUE(j["outputs_not_available"].empty());
  EXPECT_TRUE(std::filesystem::exists(dir / "life.json"));
  std::filesystem::remove_all(dir);
}

#include "fitlib/belt/stiffness.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/model/model.hpp"

namespace {
std::string write_card(const std::string& file, const std::string& kind, const nlohmann::json& options,
                       const std::vector<double>& values) {
  card::Card c;
  c.name = file;
  c.model_kind = kind;
  c.model_options = options;
  for (double v : values) {
    card::ParameterEstimate e;
    e.value = v;
    c.parameters.push_back(e);
  }
  const auto path = fitlib_test::temp_path(file);  // per process: ctest -j runs test processes at once
  card::save_card(path, c);
  return path;
}
}  // namespace

// Stiffnesses from cards: k1 = 10 tan β E33′ H/B (A.37), EI = I E22′, c = A_c E′cord, each at the
// test condition Report I names; the values come straight from the cards' models.
TEST(Stiffness, FromMaterialCards) {
  const std::vector<double> zener{8.0, 0.01, 0.05};  // relaxed modulus, τ_T, τ_ε (zener3)
  const std::string bottom = write_card("fitlib_bottom.json", "zener3", {{"mode", "uniaxial"}}, zener);
  const std::string cord = write_card("fitlib_cord.json", "zener3", {{"mode", "uniaxial"}}, {5000.0, 0.01, 0.012});
  auto s = scene::load_scene(kData + "minimal.toml");
  s.c_N.reset();
  s.k1_MPa.reset();
  s.EI_Nmm2.reset();
  s.materials = {{"bottom", bottom}, {"cord", cord}};
  const auto k = scene::resolve_stiffness(s);
  auto storage = [&](const std::string& path, double f_Hz, double amp) {
    const auto c = card::load_card(path);
    const auto v = c.values();
    model::TestCondition tc;
    tc.mode = model::TestMode::uniaxial;
    tc.frequency_Hz = f_Hz;
    tc.temperature_C = s.temperature_C;
    tc.strain_amplitude = amp;
    return c.model()->moduli(v.data(), tc).storage;
  };
  EXPECT_NEAR(k.c_N, 5.0 * storage(cord, 5.0, 0.0025), 1e-9 * k.c_N);
  EXPECT_NEAR(k.k1_MPa, belt::radial_stiffness_MPa(s.belt.wedge_half_angle_rad, storage(bottom, 34.0, 0.005),
                                                   s.belt.height_mm, s.belt.width_mm), 1e-9 * k.k1_MPa);
  EXPECT_NEAR(k.EI_Nmm2, 834.0 * storage(bottom, 34.0, 0.045), 1e-9 * k.EI_Nmm2);
  EXPECT_NE(k.k1_source.find("card"), std::string::npos);
  // Without cards or overrides: the Fritzson laws with the project's E0, E1.
  s.materials.clear();
  const auto f = scene::resolve_stiffness(s);
  EXPECT_NEAR(f.EI_Nmm2, belt::bending_stiffness_Nmm2(80.0), 1e-9);
  // A shear card without a bulk modulus gives E33 as eval and export convert it: K from its glassy
  // G0 and [belt.materials] poisson_ratio, E* = 9KG*/(3K + G*) (closed form, G0 read at 1e12 Hz).
  const std::string shear = write_card("fitlib_shear.json", "zener3", nlohmann::json::object(), zener);
  s.materials = {{"bottom", shear}};
  for (const double nu : {0.4995, 0.45}) {
    s.material_poisson_ratio = nu;
    auto shear_modulus = [&](double f_Hz) {
      const auto c = card::load_card(shear);
      model::TestCondition tc;
      tc.frequency_Hz = f_Hz;
      tc.temperature_C = s.temperature_C;
      const auto m = c.model()->moduli(c.values().data(), tc);
      return std::complex<double>(m.storage, m.loss);
    };
    const double K = 2.0 * shear_modulus(1e12).real() * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
    const std::complex<double> G = shear_modulus(34.0), E = 9.0 * K * G / (3.0 * K + G);
    const auto k_shear = scene::resolve_stiffness(s);
    EXPECT_NEAR(k_shear.EI_Nmm2, 834.0 * E.real(), 1e-6 * k_shear.EI_Nmm2) << "nu " << nu;
  }
  // A shear card that is not a series converts from its glassy modulus too: a fractional Zener
  // card's G_0 + ΔG = 11 MPa (it was refused, though eval could have answered for it).
  const std::string fz = write_card("fitlib_fz.json", "fractional-zener", nlohmann::json::object(), {1.0, 10.0, 0.01, 0.5});
  s.materials = {{"bottom", fz}};
  s.material_poisson_ratio = 0.4995;
  const double K = 2.0 * 11.0 * 1.4995 / (3.0 * 0.001);
  const auto fz_card = card::load_card(fz);
  model::TestCondition at_34Hz;
  at_34Hz.frequency_Hz = 34.0;
  at_34Hz.temperature_C = s.temperature_C;
  const auto Gm = fz_card.model()->moduli(fz_card.values().data(), at_34Hz);
  const std::complex<double> G(Gm.storage, Gm.loss), E = 9.0 * K * G / (3.0 * K + G);
  EXPECT_NEAR(scene::resolve_stiffness(s).EI_Nmm2, 834.0 * E.real(), 1e-5 * 834.0 * E.real());
}

// The Fritzson laws are straight lines through tests up to about 100 °C: beyond, a warning; where
// (6.4) has passed zero (115.8 °C), exit 3 naming the scene's temperature, the value and its source.
TEST(Stiffness, FritzsonLawsWarnBeyondTheirTestsAndStopWhereTheyPassZero) {
  auto s = scene::load_scene(kData + "minimal.toml");
  s.c_N.reset(), s.k1_MPa.reset(), s.EI_Nmm2.reset(), s.materials.clear();
  for (const double T : {20.0, 80.0, 100.0}) {
    s.temperature_C = T;
    EXPECT_TRUE(scene::resolve_stiffness(s).warnings.empty()) << T;
  }
  s.temperature_C = 110.0;
  const auto k = scene::resolve_stiffness(s);
  ASSERT_EQ(k.warnings.size(), 1u);
  EXPECT_NE(k.warnings[0].find("at 110 degC they are extrapolated"), std::string::npos) << k.warnings[0];
  EXPECT_NE(k.warnings[0].find("give a cord card under [belt.materials] (or belt.stiffness.c_N) and a bottom card "
                               "under [belt.materials] (or belt.stiffness.k1_MPa and EI_Nmm2)"), std::string::npos)
      << k.warnings[0];
  // With a bottom card the warning asks only for what is missing: the cord's.
  s.materials["bottom"] = FITLIB_SOURCE_DIR "/datasets/cards/material-1-true.json";
  const auto with_bottom = scene::resolve_stiffness(s).warnings;
  ASSERT_FALSE(with_bottom.empty());
  EXPECT_NE(with_bottom.back().find("the Fritzson stiffness laws (6.1) c are"), std::string::npos) << with_bottom.back();
  EXPECT_NE(with_bottom.back().find("; give a cord card under [belt.materials] (or belt.stiffness.c_N)"), std::string::npos)
      << with_bottom.back();
  EXPECT_EQ(with_bottom.back().find("bottom card"), std::string::npos) << with_bottom.back();
  s.materials.clear();
  s.k1_MPa = 50.0;  // an override of the one law that fails keeps the others' warning, not the error
  s.temperature_C = 120.0;
  EXPECT_EQ(scene::resolve_stiffness(s).warnings.size(), 1u);
  s.k1_MPa.reset();
  try {
    scene::resolve_stiffness(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "conditions.temperature_C");
    for (const char* part : {"k1 = -54.1", "not positive at 120 degC", "Fritzson (6.4)"})
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << part << " in " << e.what();
  }
}

TEST(Accumulation, SpectrumFromARetardationCard) {
  const std::string path = write_card("fitlib_ret.json", "retardation", {{"terms", 2}}, {1e-3, 2e-3, 5e-3, 0.01, 1.0});
  auto s = scene::load_scene(kData + "minimal.toml");
  s.materials = {{"bottom", path}};
  const auto spec = scene::scene_spectrum(s, "material:bottom");
  ASSERT_EQ(spec.compliances.size(), 2u);
  EXPECT_DOUBLE_EQ(spec.glassy_compliance, 1e-3);
  EXPECT_DOUBLE_EQ(spec.compliances[1], 5e-3);
  EXPECT_DOUBLE_EQ(spec.times_s[1], 1.0);
  // A card without a retardation spectrum is a clear error naming the key.
  const std::string z = write_card("fitlib_z.json", "zener3", nlohmann::json::object(), {8.0, 0.01, 0.05});
  s.materials = {{"bottom", z}};
  try {
    scene::scene_spectrum(s, "material:bottom");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "accumulation.spectrum");
    // It says the role was the default's, and what else to give.
    for (const char* said : {"of the 'bottom' card (material:bottom, the default)", "set [accumulation] spectrum to a shape"})
      EXPECT_NE(std::string(e.what()).find(said), std::string::npos) << said << " in " << e.what();
  }
}

TEST(Planner, TensionTestOutputRunsOnlyTheSimulation) {
  const auto s = scene::load_scene(kData + "tension_test.toml");
  const auto r = scene::run_scene(s);
  EXPECT_FALSE(r.cycle.has_value());  // no load history asked for
  ASSERT_TRUE(r.tension_test.has_value());
  const auto& test = r.tension_test->result;
  EXPECT_GT(test.loading.back().span_tension_N, 0.0);
  EXPECT_LE(test.unloading.back().span_tension_N, 1e-9 + test.unloading.front().span_tension_N);
  const std::string csv = scene::tension_test_csv(test);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "phase,t_s,elongation_mm,span_tension_N,boundary_deg");
}

// Issue 8: the Sorge–Cammalleri steady drive used F − ρAv² even with inertia = false (74.24°).
// With the static tensions 500 / 200 N (ratio 2.5 as in the paper's Fig. 5) the adhesion arc is
// 75.00°; with inertia on, ρAv² lowers both tensions and the arc changes.
TEST(Planner, SteadyDriveUsesStaticTensionsWithoutInertia) {
  auto s = scene::load_scene(FITLIB_SOURCE_DIR "/datasets/drives/sorge-cammalleri-fig5.toml");
  const auto r = scene::run_scene(s);
  const double deg = 180.0 / M_PI;
  const auto& v = r.viscoelastic->solution;
  EXPECT_NEAR(v.driver.adhesion_rad * deg, 75.00, 0.005);
  EXPECT_NEAR(v.driven.adhesion_rad * deg, 75.00, 0.005);
  s.effects["inertia"] = true;
  const auto with_inertia = scene::run_scene(s);
  EXPECT_LT(with_inertia.viscoelastic->solution.driver.adhesion_rad * deg, 74.5);
}

TEST(SceneParse, SegmentThreadsReachTheSolverAndDefaultToTheSolversChoice) {
  const auto set = scene::parse_scene(minimal_text() + "[segment]\nstrain = 0.01\nthreads = 3\n", "x.toml");
  ASSERT_TRUE(set.segment.has_value());
  EXPECT_EQ(set.segment->setup.solver.threads, 3);
  const auto unset = scene::parse_scene(minimal_text() + "[segment]\nstrain = 0.01\n", "x.toml");
  EXPECT_EQ(unset.segment->setup.solver.threads, 0);  // min(2, hardware) at the run
  EXPECT_EQ(parse_error(minimal_text() + "[segment]\nthreads = 0\n").key(), "segment.threads");
  EXPECT_EQ(parse_error(minimal_text() + "[segment]\nthreads = 2.5\n").key(), "segment.threads");
}

// A sweep runs its cases side by side and caps each case's segment at one thread; a scene's own
// [segment] threads and the solver's default stay below the cap.
TEST(SceneParse, SegmentThreadCapBoundsTheSceneAndTheDefaultThreads) {
  auto s = scene::parse_scene(minimal_text(), "x.toml");
  EXPECT_EQ(scene::segment_threads(s), segment::solver_threads(segment::SolverKnobs{}));
  s.segment_thread_cap = 1;
  EXPECT_EQ(scene::segment_threads(s), 1);
  s = scene::parse_scene(minimal_text() + "[segment]\nstrain = 0.01\nthreads = 3\n", "x.toml");
  EXPECT_EQ(scene::segment_threads(s), 3);
  s.segment_thread_cap = 2;
  EXPECT_EQ(scene::segment_threads(s), 2);
}
