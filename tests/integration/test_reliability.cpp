// Regression tests of issue 12 (reliability): each input below once crashed, wrote NaN/inf with
// exit 0, gave the wrong exit code, named no file or key, ran for hours or left partial outputs.
#include <chrono>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace fs = std::filesystem;

namespace {

std::string write(const std::string& name, const std::string& text) {
  const auto path = temp_file(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// No NaN or inf anywhere in what a run printed.
bool finite_text(const std::string& text) {
  return !contains(text, "nan") && !contains(text, "inf");
}

// A clean 60 Hz record (stress/strain), with `stress_scale` and `strain_scale` applied.
std::string waveform_record(double stress_scale, double strain_scale, const std::string& metadata = "") {
  std::string text = "# mode = uniaxial\n" + metadata + "time_s,stress_MPa,strain\n";
  const int n = 2048;
  for (int i = 0; i < n; ++i) {
    const double t = i / (60.0 * 256.0);
    const double phase = 2.0 * 3.141592653589793 * 60.0 * t;
    char line[128];
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", t, stress_scale * std::sin(phase + 0.2),
                  strain_scale * std::sin(phase));
    text += line;
  }
  return text;
}

std::string card_with(const std::function<void(nlohmann::json&)>& edit) {
  auto card = nlohmann::json::parse(slurp(source_path("datasets/cards/synthetic-prony-shear-true.json")));
  edit(card);
  return card.dump(1);
}

}  // namespace

// ---- waveform ----

TEST(Reliability, WaveformLongCommentLineIsNotAStackOverflow) {
  const auto path = write("long_comment.csv", "#" + std::string(30000, 'x') + "\n" + waveform_record(1.0, 0.01));
  const auto r = run_fitcli("waveform --signals " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;  // was 139 (regular expression recursion)
}

TEST(Reliability, WaveformZeroStressIsBadInputAndKeepsTheOldOutput) {
  const auto out = write("kept.csv", "previous content\n");
  const auto path = write("zero_stress.csv", waveform_record(0.0, 0.01));
  const auto r = run_fitcli("waveform --signals " + path + " --out " + out);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, path)) << r.err;
  EXPECT_EQ(slurp(out), "previous content\n");
}

TEST(Reliability, WaveformDenormalStrainAmplitudeWritesNoInf) {
  const auto path = write("tiny_strain.csv", waveform_record(1.0, 1e-310));
  const auto r = run_fitcli("waveform --signals " + path + " --json");
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, path)) << r.err;
  EXPECT_TRUE(finite_text(r.out)) << r.out;
}

TEST(Reliability, WaveformHugeSpecimenCountIsBadInputNamingTheKey) {
  const auto path = write("n_specimens.csv", waveform_record(1.0, 0.01, "# n_specimens = 1e10\n"));
  const auto r = run_fitcli("waveform --signals " + path);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "n_specimens")) << r.err;
}

TEST(Reliability, WaveformTinyKnownFrequencyIsBadInputNamingTheFile) {
  const auto path = write("slow.csv", waveform_record(1.0, 0.01));
  const auto r = run_fitcli("waveform --signals " + path + " --frequency-hz 1e-300");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, path)) << r.err;
}

TEST(Reliability, WaveformAnalysisErrorsNameTheFile) {
  const auto path = write("flat.csv", waveform_record(1.0, 0.0));
  const auto r = run_fitcli("waveform --signals " + path);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, path + ":")) << r.err;
}

// ---- cards and eval ----

TEST(Reliability, CardFieldsOfTheWrongTypeNameFileAndKey) {
  const std::vector<std::pair<std::string, nlohmann::json>> cases = {
      {"fixed", "yes"}, {"ci95", {1.0, "a"}}, {"name", 3}, {"std_error_reason", 5}};
  for (const auto& [key, value] : cases) {
    const auto path = write("card_" + key + ".json",
                            card_with([&, key = key, value = value](nlohmann::json& c) { c["parameters"][1][key] = value; }));
    const auto r = run_fitcli("eval --card " + path + " --mode shear --frequency-hz 1");
    EXPECT_EQ(r.exit_code, 3) << key << ": " << r.err;
    EXPECT_TRUE(contains(r.err, path)) << r.err;
    EXPECT_TRUE(contains(r.err, "parameters[1]." + key)) << r.err;
  }
}

TEST(Reliability, NumberBeyondTheDoubleRangeNamesFileAndKeyInEveryJsonReader) {
  std::string card = card_with([](nlohmann::json&) {});
  card.replace(card.find("\"value\": 2.0"), 12, "\"value\": 1e309");
  const auto card_path = write("big_card.json", card);
  auto r = run_fitcli("eval --card " + card_path + " --mode shear --frequency-hz 1");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, card_path) && contains(r.err, "parameters[0].value")) << r.err;

  const auto schedule = write("big_schedule.json", R"({"stages": [{"free": ["*"], "max_iterations": 1e400}]})");
  r = run_fitcli("fit --data " + source_path("datasets/materials/material-2.csv") +
                 " --model fritzson-iso --backend staged --schedule " + schedule);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, schedule) && contains(r.err, "stages[0].max_iterations")) << r.err;

  const auto surface_path = write("big_surface.json", R"({"schema": "fitlib.surface/1", "axes": [{"name": "x",
      "transform": "linear", "interval": [0, 1], "degree": 1}], "control_points": {"values": [1e999, 1]}})");
  r = run_fitcli("surface eval --surface " + surface_path + " --at 1");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, surface_path) && contains(r.err, "control_points.values[0]")) << r.err;

  const auto signals = write("sidecar_signals.csv", waveform_record(1.0, 0.01));
  const auto sidecar = write("big_sidecar.json", R"({"temperature_C": 1e309})");
  r = run_fitcli("waveform --signals " + signals + " --specimen " + sidecar);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, sidecar) && contains(r.err, "temperature_C")) << r.err;
}

TEST(Reliability, CardValuesThatOverflowTheModuliAreBadInput) {
  for (const auto& [name, value] : std::vector<std::pair<std::string, double>>{{"tau_1", 1e200}, {"G_inf", 1.7e308}}) {
    const auto path = write("overflow_" + name + ".json", card_with([&, name = name, value = value](nlohmann::json& c) {
                              for (auto& p : c["parameters"])
                                if (p["name"] == name) p["value"] = value;
                            }));
    const auto r = run_fitcli("eval --card " + path + " --mode shear --frequency-hz 1");
    EXPECT_EQ(r.exit_code, 3) << name << ": " << r.out << r.err;
    EXPECT_TRUE(contains(r.err, path) && contains(r.err, ".value")) << r.err;
    EXPECT_TRUE(finite_text(r.out)) << r.out;
  }
}

TEST(Reliability, EvalAtAnOverflowingFrequencyIsANumericalFailureNotNan) {
  const auto r = run_fitcli("eval --card " + source_path("datasets/cards/synthetic-prony-shear-true.json") +
                            " --mode shear --frequency-hz 1e308");
  EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
  EXPECT_TRUE(finite_text(r.out)) << r.out;
  EXPECT_TRUE(contains(r.err, "1e+308 Hz")) << r.err;
}

TEST(Reliability, MissingInputFileIsBadInput) {
  const auto missing = temp_file("does-not-exist.json");
  EXPECT_EQ(run_fitcli("eval --card " + missing + " --mode shear --frequency-hz 1").exit_code, 3);
  EXPECT_EQ(run_fitcli("export --card " + missing + " --format abaqus").exit_code, 3);
  EXPECT_EQ(run_fitcli("fit --data " + temp_file("missing.csv") + " --model prony").exit_code, 3);
  const auto r = run_fitcli("surface eval --surface " + missing + " --at 1");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, missing)) << r.err;
}

// ---- tables and fits ----

TEST(Reliability, TableFrequencyNearTheDoubleLimitIsBadInputNamingFileAndLine) {
  const auto path = write("huge_frequency.csv",
                          "mode,frequency_Hz,storage_MPa,loss_MPa\nshear,1,2,0.5\nshear,1e308,3,0.6\nshear,10,4,0.7\n");
  const auto r = run_fitcli("fit --data " + path + " --model prony --terms 1");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, path + ":3:2")) << r.err;
}

TEST(Reliability, AllZeroWeightsAreBadInputNamingTheFile) {
  const auto path = write("zero_weights.csv",
                          "mode,frequency_Hz,storage_MPa,loss_MPa,weight\nshear,1,2,0.5,0\nshear,10,4,0.7,0\n");
  const auto r = run_fitcli("fit --data " + path + " --model prony --terms 1");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, path) && contains(r.err, "weight")) << r.err;
}

TEST(Reliability, TableWithALineLongerThan16MiBIsRead) {
  // fast-cpp-csv-parser's LineReader (3 x 16 MiB buffers) refused lines above 16 MiB.
  const auto path = write("long_line.csv", "# " + std::string(17 << 20, 'x') +
                                               "\nmode,frequency_Hz,storage_MPa,loss_MPa\nshear,1,2,0.5\nshear,10,4,0.7\n");
  const auto r = run_fitcli("fit --data " + path + " --model prony --terms 1 --backend nnls");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(Reliability, ScheduleErrorsNameTheScheduleFile) {
  const auto schedule = write("selects_nothing.json", R"({"stages": [{"free": ["no_such_parameter"]}]})");
  const auto r = run_fitcli("fit --data " + source_path("datasets/materials/material-2.csv") +
                            " --model fritzson-iso --backend staged --schedule " + schedule);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, schedule) && contains(r.err, "stages[0].free[0]")) << r.err;
}

// `args` + " --out <missing folder>/x" fails naming that folder and leaves no `other_output`.
void expect_no_partial_output(const std::string& args, const std::string& other_output) {
  const auto r = run_fitcli(args + " --out " + temp_file("no-such-dir/x"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_FALSE(fs::exists(other_output)) << args;
  EXPECT_TRUE(contains(r.err, "no-such-dir")) << r.err;
}

TEST(Reliability, FailedMasterCurveFitLeavesNoShiftTable) {
  const auto shifts = temp_file("partial_shifts.csv");
  expect_no_partial_output("fit --data " + source_path("datasets/materials/pyvisco-freq-raw.csv") +
                               " --format pyvisco --model prony --terms 4 --master-curve --reference-c -5 --shifts-out " + shifts,
                           shifts);
}

// ---- surfaces ----

TEST(Reliability, FailedSurfaceGridLeavesNoSurface) {
  const auto surface_out = temp_file("partial_surface.json");
  expect_no_partial_output("surface grid --card " + source_path("datasets/cards/synthetic-prony-shear-true.json") +
                               " --frequency-hz 1,10,100 --temperature-c 23 --amplitude 0.01 --surface-out " + surface_out,
                           surface_out);
}

TEST(Reliability, SurfaceWithSixtyFourAxesIsBadInputNotZero) {
  nlohmann::json axes = nlohmann::json::array();
  for (int k = 0; k < 64; ++k)
    axes.push_back({{"name", "x" + std::to_string(k)}, {"transform", "linear"}, {"interval", {0, 1}}, {"degree", 1}});
  const nlohmann::json s = {{"schema", "fitlib.surface/1"}, {"axes", axes}, {"control_points", {{"values", nlohmann::json::array()}}}};
  const auto path = write("axes64.json", s.dump());
  std::string at = "0.5";
  for (int k = 1; k < 64; ++k) at += ",0.5";
  const auto r = run_fitcli("surface eval --surface " + path + " --at " + at);
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, path) && contains(r.err, "axes")) << r.err;
}

TEST(Reliability, SurfaceGradientOverflowIsANumericalFailureNotInf) {
  const nlohmann::json s = {
      {"schema", "fitlib.surface/1"},
      {"axes", {{{"name", "x"}, {"transform", "linear"}, {"interval", {0, 1e-300}}, {"degree", 1}}}},
      {"control_points", {{"values", {-1e300, 1e300}}}}};
  const auto path = write("steep.json", s.dump());
  const auto r = run_fitcli("surface eval --surface " + path + " --at 0 --gradient");
  EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
  EXPECT_TRUE(finite_text(r.out)) << r.out;
}

// ---- belt scenes ----

std::string minimal_scene(const std::string& extra) {
  return slurp(source_path("tests/data/scenes/minimal.toml")) + extra;
}

TEST(Reliability, SceneCentreAtInfinityIsBadInputNamingTheKey) {
  std::string scene = slurp(source_path("tests/data/scenes/three_pulley.toml"));
  const std::string centre = "center_mm = [400, 0]";
  ASSERT_NE(scene.find(centre), std::string::npos);
  scene.replace(scene.find(centre), centre.size(), "center_mm = [inf, 0]");
  const auto path = write("center_inf.toml", scene);
  const auto r = run_fitcli("belt --scene " + path + " --out-dir " + temp_file("center_inf_out"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, path) && contains(r.err, "center_mm")) << r.err;
}

TEST(Reliability, BeltOutputFolderThatCannotBeCreatedIsBadInput) {
  const auto file = write("a_file", "x");
  const auto r = run_fitcli("belt --scene " + source_path("tests/data/scenes/minimal.toml") + " --out-dir " + file + "/sub");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, file)) << r.err;
}

TEST(Reliability, BeltErrorsNameTheSceneFile) {
  std::string scene = slurp(source_path("tests/data/scenes/minimal.toml"));
  scene.replace(scene.find("torque_Nm = 15"), 14, "torque_Nm = 5000");
  const auto path = write("slipping.toml", scene);
  const auto r = run_fitcli("belt --scene " + path + " --out-dir " + temp_file("slipping_out"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, path + ":")) << r.err;
}

TEST(Reliability, AccumulationWorkBeyondTheCapIsRefusedAtOnce) {
  const auto path = write("accumulation_cap.toml",
                          minimal_scene("[outputs]\nstrain_accumulation = true\n[accumulation]\nspectrum = \"gauss\"\n"
                                        "cycle_points = 100000\nomega_points = 100000\n"));
  const auto start = std::chrono::steady_clock::now();
  const auto r = run_fitcli("belt --scene " + path + " --out-dir " + temp_file("accumulation_cap_out"));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "accumulation.omega_points")) << r.err;
}

TEST(Reliability, TensionTestWorkBeyondTheCapIsRefusedAtOnce) {
  std::string scene = slurp(source_path("tests/data/scenes/tension_test.toml"));
  scene.replace(scene.find("nodes = 60"), 10, "nodes = 100000");
  scene.replace(scene.find("steps = 300"), 11, "steps = 10000000");
  const auto path = write("tension_cap.toml", scene);
  const auto start = std::chrono::steady_clock::now();
  const auto r = run_fitcli("belt --scene " + path + " --out-dir " + temp_file("tension_cap_out"));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "tension_test.nodes")) << r.err;
}
