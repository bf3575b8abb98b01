// Sweep files, grid enumeration and rows (docs/sweep.md).
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/sweep.hpp"
#include "../../../fitlib/src/scene/sweep_case.hpp"
#include "common/temp_path.hpp"

namespace {

using fitlib::scene::parse_sweep;

// Sweep text "parsed" as if it were a file in datasets/sweeps (its relative paths resolve there).
const std::string kSource = std::string(FITLIB_SOURCE_DIR) + "/datasets/sweeps/unit-test.toml";

std::string grid_text(const std::string& axes, const std::string& columns = R"(["max_tension_N"])") {
  return "scenes = [\"../drives/ref-0500-medium.toml\", \"../drives/ref-0500-heavy.toml\"]\n" + axes +
         "\n[outputs]\ncolumns = " + columns + "\n";
}

const std::string kTwoAxes = R"(
[[axis]]
key = "conditions.temperature_C"
values = [20, 60.5, 80]

[[axis]]
key = "drive.pulleys[0].speed_rpm"
values = [1500, 3000]
)";

fitlib::core::InputError input_error_of(const std::string& text) {
  try {
    parse_sweep(text, kSource);
  } catch (const fitlib::core::InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return fitlib::core::InputError("none");
}

TEST(Sweep, EnumeratesScenesSlowestLastAxisFastest) {
  const auto s = parse_sweep(grid_text(kTwoAxes), kSource);
  ASSERT_EQ(s.case_count, 12u);
  for (std::size_t scene = 0, i = 0; scene < 2; ++scene)
    for (std::size_t t = 0; t < 3; ++t)
      for (std::size_t v = 0; v < 2; ++v, ++i) {
        const auto c = fitlib::scene::sweep_case(s, i);
        EXPECT_EQ(c.index, i);
        EXPECT_EQ(c.scene, scene) << i;
        EXPECT_EQ(c.value, (std::vector<std::size_t>{t, v})) << i;
      }
  EXPECT_THROW(fitlib::scene::sweep_case(s, 12), std::out_of_range);
}

TEST(Sweep, HeaderNamesAxesByKeyAndLabelsAsWritten) {
  const auto s = parse_sweep(grid_text(kTwoAxes), kSource);
  EXPECT_EQ(fitlib::scene::sweep_header(s),
            (std::vector<std::string>{"case", "scene", "conditions.temperature_C", "drive.pulleys[0].speed_rpm",
                                      "max_tension_N", "status", "message"}));
  EXPECT_EQ(s.axes[0].labels, (std::vector<std::string>{"20", "60.5", "80"}));
  EXPECT_EQ(s.scene_labels[1], "../drives/ref-0500-heavy.toml");
}

// The row's figure equals the same scene edited by hand and run directly (an independent path:
// text substitution instead of key paths).
TEST(Sweep, RowEqualsTheHandEditedSceneRun) {
  const auto s = parse_sweep(grid_text(R"(
[[axis]]
key = "drive.torque_Nm"
values = [10, 30]
)", R"(["max_tension_N", "min_tension_N"])"), kSource);
  const std::string path = std::string(FITLIB_SOURCE_DIR) + "/datasets/drives/ref-0500-heavy.toml";
  std::string text = fitlib::core::read_file(path);
  const auto at = text.find("torque_Nm = 30");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 14, "torque_Nm = 10");
  const auto r = fitlib::scene::run_scene(fitlib::scene::parse_scene(text, path));
  double hi = -INFINITY, lo = INFINITY;
  for (const auto& x : r.cycle->samples) hi = std::max(hi, x.F_N), lo = std::min(lo, x.F_N);
  const auto fields = fitlib::scene::split_csv_row(fitlib::scene::sweep_row(s, 2));  // heavy, 10 N·m
  ASSERT_EQ(fields.size(), 7u);
  EXPECT_EQ(fields[0], "2");
  EXPECT_EQ(fields[2], "10");
  EXPECT_EQ(fields[3], fitlib::core::format_number(hi));
  EXPECT_EQ(fields[4], fitlib::core::format_number(lo));
  EXPECT_EQ(fields[5], "ok");
  EXPECT_EQ(fields[6], "");
  EXPECT_NE(fitlib::scene::sweep_row(s, 3), fitlib::scene::sweep_row(s, 2));
}

// The heat build-up's and the life distribution's columns (docs/sweep.md, issue 34 item 5): each
// row's belt_temperature_C, heat_W, B10_h and separation_B10_h are the same case's scene run
// directly (the medium drive edited by hand to the torque), and a scene without heat build-up leaves
// the heat columns empty but keeps its B10.
TEST(Sweep, BeltTemperatureAndB10ColumnsAreTheCasesOwnRun) {
  namespace fatigue = fitlib::fatigue;
  fatigue::FatigueCard card = fatigue::default_card();
  card.separation.scatter = fatigue::LifeScatter{"lognormal", 0.25, 10};
  card.separation.covariance = fatigue::LawCovariance{{{1e-3, 0.0, 0.0}, {0.0, 0.04, 0.0}, {0.0, 0.0, 1e-5}}};
  card.levels.clear();  // the beam run reads these modes
  const std::string dir = fitlib_test::temp_dir();
  fatigue::save_card(dir + "scatter-card.json", card);
  const std::string medium = fitlib::core::read_file(std::string(FITLIB_SOURCE_DIR) + "/datasets/drives/ref-0500-medium.toml");
  auto edited = [&](bool heat, int torque) {
    std::string t = medium;
    auto put = [&](const std::string& what, const std::string& by) {
      const auto at = t.find(what);
      EXPECT_NE(at, std::string::npos) << what;
      t.replace(at, what.size(), by);
    };
    put("torque_Nm = 15", "torque_Nm = " + std::to_string(torque));
    if (heat) put("[conditions]\n", "[conditions]\nambient_C = 25\n"), put("[effects]\n", "[effects]\nheat_buildup = true\n");
    return t + "\n[life]\nfidelity = \"beam\"\ncard = \"scatter-card.json\"\n";
  };
  for (bool heat : {true, false})
    fitlib::core::write_file_atomically(dir + (heat ? "heat.toml" : "fixed.toml"), edited(heat, 15));
  const auto s = parse_sweep("scenes = [\"heat.toml\", \"fixed.toml\"]\n[[axis]]\nkey = \"drive.torque_Nm\"\n"
                             "values = [10, 20]\n[outputs]\ncolumns = [\"belt_temperature_C\", \"heat_W\", \"B10_h\", "
                             "\"separation_B10_h\"]\n", dir + "heat-sweep.toml");
  ASSERT_EQ(s.case_count, 4u);
  std::string hot[2];
  for (std::size_t i = 0; i < 4; ++i) {
    const bool heat = i < 2;
    const int torque = i % 2 == 0 ? 10 : 20;
    const auto r = fitlib::scene::run_life(fitlib::scene::parse_scene(edited(heat, torque), dir + "direct.toml"));
    ASSERT_EQ(heat, r.heat.has_value()) << i;
    const auto fields = fitlib::scene::split_csv_row(fitlib::scene::sweep_row(s, i));
    ASSERT_EQ(fields.size(), 9u) << i;
    EXPECT_EQ(fields[7], "ok") << fields[8];
    EXPECT_EQ(fields[3], heat ? fitlib::core::format_number(r.heat->temperature_C) : "") << i;
    EXPECT_EQ(fields[4], heat ? fitlib::core::format_number(r.heat->heat_in_W) : "") << i;
    ASSERT_EQ(r.life->distribution.size(), 1u);  // separation's law alone states a scatter
    const auto& d = r.life->distribution[0];
    EXPECT_EQ(fields[6], fitlib::core::format_number(d.b10.h)) << i;
    EXPECT_EQ(fields[5], r.life->report.governing == "separation" ? fields[6] : "") << i;
    if (heat) hot[i] = fields[3];
  }
  EXPECT_GT(std::stod(hot[1]), std::stod(hot[0]));  // hotter at the larger torque
  EXPECT_GT(std::stod(hot[0]), 25.0);
}

TEST(Sweep, CaseTheDriveCannotCarryIsARowNotAFailure) {
  const auto s = parse_sweep(grid_text(R"(
[[axis]]
key = "drive.torque_Nm"
values = [10, 5000]
)"), kSource);
  const auto fields = fitlib::scene::split_csv_row(fitlib::scene::sweep_row(s, 1));
  ASSERT_EQ(fields.size(), 6u);
  EXPECT_EQ(fields[3], "");
  EXPECT_EQ(fields[4], "input_error");
  EXPECT_NE(fields[5].find("ref-0500-medium.toml"), std::string::npos) << fields[5];
}

// An ok row's message carries the scene's warnings: at 110 degC the Fritzson stiffness laws are
// extrapolated (docs/sweep.md).
TEST(Sweep, OkRowsMessageCarriesTheScenesWarnings) {
  const auto s = parse_sweep(grid_text("[[axis]]\nkey = \"conditions.temperature_C\"\nvalues = [80, 110]\n"), kSource);
  const auto at80 = fitlib::scene::split_csv_row(fitlib::scene::sweep_row(s, 0));
  const auto at110 = fitlib::scene::split_csv_row(fitlib::scene::sweep_row(s, 1));
  ASSERT_EQ(at110.size(), 6u);
  EXPECT_EQ(at80[4], "ok");
  EXPECT_EQ(at80[5], "");
  EXPECT_EQ(at110[4], "ok");
  EXPECT_NE(at110[3], "");
  EXPECT_EQ(at110[5].rfind("warning: the Fritzson stiffness laws", 0), 0u) << at110[5];
}

TEST(Sweep, CsvFieldsRoundTrip) {
  const std::vector<std::string> fields{"a", "b,c", "say \"hi\"", "", "1e+06"};
  std::string row;
  for (std::size_t i = 0; i < fields.size(); ++i) row += (i ? "," : "") + fitlib::scene::csv_field(fields[i]);
  EXPECT_EQ(row, "a,\"b,c\",\"say \"\"hi\"\"\",,1e+06");
  EXPECT_EQ(fitlib::scene::split_csv_row(row), fields);
}

TEST(Sweep, HashChangesWithTheSweepAndTheFilesItNames) {
  const auto a = parse_sweep(grid_text(kTwoAxes), kSource);
  const auto b = parse_sweep(grid_text(kTwoAxes) + "# edited\n", kSource);
  EXPECT_EQ(a.sha256.size(), 64u);
  EXPECT_NE(a.sha256, b.sha256);
  EXPECT_EQ(a.sha256, parse_sweep(grid_text(kTwoAxes), kSource).sha256);
}

TEST(SweepFile, ErrorsNameFileLineAndKey) {
  auto e = input_error_of(grid_text(kTwoAxes, R"(["max_tension_N", "max_tenson_N"])"));
  EXPECT_EQ(e.key(), "outputs.columns[1]");
  EXPECT_EQ(e.file(), kSource);
  EXPECT_NE(std::string(e.what()).find("known: "), std::string::npos) << e.what();
  for (const std::string& name : fitlib::scene::sweep_column_names())  // the message lists them all
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << name;
  e = input_error_of(grid_text("[[axis]]\nkey = \"conditions.temperature_C\"\nvalues = [20, -500]\n"));
  EXPECT_EQ(e.key(), "axis[0].values[1]");
  EXPECT_EQ(e.line(), 4);
  EXPECT_NE(std::string(e.what()).find("temperature_C"), std::string::npos) << e.what();
  e = input_error_of(grid_text("[[axis]]\nkey = \"drive.pulleys.speed_rpm\"\nvalues = [1]\n"));
  EXPECT_EQ(e.key(), "axis[0].values[0]");
  e = input_error_of(grid_text("[[axis]]\nkey = \"conditions.temprature_C\"\nvalues = [1]\n"));
  EXPECT_NE(std::string(e.what()).find("temprature_C"), std::string::npos) << e.what();
  e = input_error_of(grid_text("[[axis]]\ncard = \"top\"\nvalues = [\"x.json\"]\n"));
  EXPECT_EQ(e.key(), "axis[0].card");
  e = input_error_of(grid_text("[[axis]]\nkey = \"drive.torque_Nm\"\nvalues = []\n"));
  EXPECT_EQ(e.key(), "axis[0].values");
  e = input_error_of("scenes = [\"../drives/none.toml\"]\n[outputs]\ncolumns = [\"life_h\"]\n");
  EXPECT_NE(std::string(e.what()).find("none.toml"), std::string::npos) << e.what();
  e = input_error_of(grid_text(kTwoAxes) + "threads = 4\n");
  EXPECT_EQ(e.key(), "outputs.threads");  // after [outputs]: a key of that table
  EXPECT_NE(std::string(e.what()).find("this table takes columns"), std::string::npos) << e.what();
}

// A sweep file without [outputs] asks for the load cycle's headline figures and the life per mode;
// an [outputs] table without columns is still an error naming the key.
TEST(SweepFile, WithoutOutputsTheDefaultColumnsAreTheLifePerMode) {
  const std::string text = "scenes = [\"../drives/ref-0500-medium.toml\"]\n" + kTwoAxes;
  const auto s = parse_sweep(text, kSource);
  EXPECT_EQ(s.columns, (std::vector<std::string>{"max_tension_N", "max_sliding_arc_deg", "fidelity",
                                                 "governing_mode", "life_h", "radial_crack_life_h",
                                                 "separation_life_h"}));
  for (const std::string& c : s.columns)  // each a known column
    EXPECT_NE(std::find(fitlib::scene::sweep_column_names().begin(), fitlib::scene::sweep_column_names().end(), c),
              fitlib::scene::sweep_column_names().end()) << c;
  EXPECT_EQ(input_error_of(text + "[outputs]\n").key(), "outputs.columns");
}

TEST(SweepFile, GridAboveTheWorkCapIsRefused) {
  std::string big = "[[axis]]\nkey = \"conditions.temperature_C\"\nvalues = [";
  for (int i = 0; i < 1001; ++i) big += (i ? ", " : "") + std::to_string(i % 100);
  big += "]\n[[axis]]\nkey = \"drive.torque_Nm\"\nvalues = [";
  for (int i = 0; i < 500; ++i) big += (i ? ", " : "") + std::to_string(i % 30);
  big += "]\n";
  const auto e = input_error_of(grid_text(big));  // 2 × 1001 × 500 > 1e6
  EXPECT_EQ(e.key(), "axis");
  EXPECT_NE(std::string(e.what()).find("work cap"), std::string::npos) << e.what();
}

}  // namespace

// Every case runs its segment on one thread: the sweep's threads and MPI ranks already run the
// cases side by side (docs/sweep.md "Running").
TEST(Sweep, EveryCaseCapsTheSegmentAtOneThread) {
  const auto sweep = parse_sweep(grid_text(kTwoAxes), kSource);
  for (std::size_t i = 0; i < sweep.case_count; ++i) {
    const auto s = fitlib::scene::case_scene(sweep, fitlib::scene::sweep_case(sweep, i));
    EXPECT_EQ(s.segment_thread_cap, 1);
    EXPECT_EQ(fitlib::scene::segment_threads(s), 1);
  }
}
