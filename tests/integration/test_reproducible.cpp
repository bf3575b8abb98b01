// Same input and seed → the same output bytes, for every subcommand, model family and backend
// (README; wall times only under --record-timing). Each command runs twice into the same path.
#include <filesystem>

#include "cli_runner.hpp"

namespace fs = std::filesystem;

namespace {

// Runs `args` (which writes `outputs`) twice; every output file must be byte-identical (the
// human-readable summary on stdout may show wall times).
void expect_reproducible(const std::string& args, const std::vector<std::string>& outputs) {
  std::vector<std::string> first;
  const auto a = run_fitcli(args);
  ASSERT_EQ(a.exit_code, 0) << args << "\n" << a.err;
  for (const auto& o : outputs) {
    first.push_back(slurp(o));
    fs::remove_all(o);
  }
  const auto b = run_fitcli(args);
  ASSERT_EQ(b.exit_code, 0) << args << "\n" << b.err;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    EXPECT_FALSE(first[i].empty()) << outputs[i];
    EXPECT_EQ(first[i], slurp(outputs[i])) << args << ": " << outputs[i] << " differs";
  }
}

const std::string kShearTable = source_path("datasets/materials/synthetic-prony-shear.csv");
const std::string kShearCard = source_path("datasets/cards/synthetic-prony-shear-true.json");

}  // namespace

TEST(Reproducible, FitWithEveryBackend) {
  for (const std::string backend : {"nnls", "ceres", "nlopt", "auto"}) {
    const auto out = temp_file("repro-" + backend + ".json");
    expect_reproducible("fit --data " + kShearTable + " --model prony --terms 3 --backend " + backend +
                            " --seed 7 --out " + out,
                        {out});
  }
  const auto fz = temp_file("repro-fz.json");
  expect_reproducible("fit --data " + kShearTable + " --model fractional-zener --out " + fz, {fz});
}

TEST(Reproducible, StagedFitCardHasNoWallTimes) {
  const auto out = temp_file("repro-staged.json");
  expect_reproducible("fit --data " + source_path("datasets/materials/material-2.csv") +
                          " --model fritzson-iso --backend staged --schedule " +
                          source_path("datasets/schedules/fritzson-iso.json") + " --out " + out,
                      {out});
  EXPECT_EQ(slurp(out).find(" s\""), std::string::npos) << "a wall time in the card's messages";
}

TEST(Reproducible, MasterCurveFitAndShiftTable) {
  const auto out = temp_file("repro-master.json"), shifts = temp_file("repro-shifts.csv");
  expect_reproducible("fit --data " + source_path("datasets/materials/pyvisco-freq-raw.csv") +
                          " --format pyvisco --model prony --terms 8 --master-curve --reference-c -5 --shifts-out " +
                          shifts + " --out " + out,
                      {out, shifts});
}

TEST(Reproducible, EvalExportSynth) {
  const auto curve = temp_file("repro-curve.csv"), inp = temp_file("repro.inp"), table = temp_file("repro-synth.csv");
  expect_reproducible("eval --card " + kShearCard + " --mode shear --frequency-hz 0.1,1,10 --out " + curve, {curve});
  expect_reproducible("export --card " + kShearCard + " --format abaqus --out " + inp, {inp});
  expect_reproducible("synth --card " + kShearCard + " --frequency-hz 1,10,100 --noise 0.01 --seed 5 --out " + table,
                      {table});
}

TEST(Reproducible, WaveformAndMaterialPoint) {
  const auto row = temp_file("repro-row.csv"), loops = temp_file("repro-loops.csv");
  expect_reproducible("waveform --signals " + source_path("tests/data/waveforms/stress_strain_harmonic_60Hz.csv") +
                          " --out " + row,
                      {row});
  expect_reproducible("material-point --card " + source_path("datasets/cards/material-2-true.json") +
                          " --case 7.1 --steps-per-cycle 64 --out " + loops,
                      {loops});
}

TEST(Reproducible, SurfaceFitEvalGrid) {
  const auto s = temp_file("repro-surface.json"), values = temp_file("repro-values.csv");
  const auto grid = temp_file("repro-grid.csv"), grid_surface = temp_file("repro-grid-surface.json");
  expect_reproducible("surface fit --data " + source_path("tests/data/surface/shear_3x3x3_missing.csv") +
                          " --x strain_amplitude --x frequency_Hz --x temperature_C --y storage_MPa --out " + s,
                      {s});
  expect_reproducible("surface eval --surface " + s + " --at 0.015,10,60 --gradient --out " + values, {values});
  expect_reproducible("surface grid --card " + kShearCard +
                          " --frequency-hz 1,10,100 --temperature-c 23 --amplitude 0.01 --out " + grid +
                          " --surface-out " + grid_surface,
                      {grid, grid_surface});
}

TEST(Reproducible, BeltAndAccumulate) {
  const auto dir = temp_file("repro-belt"), map = temp_file("repro-map.csv");
  expect_reproducible("belt --scene " + source_path("tests/data/scenes/full.toml") + " --out-dir " + dir,
                      {dir + "/load_history.csv", dir + "/accumulation.csv", dir + "/summary.json"});
  expect_reproducible("accumulate --spectrum gauss --out " + map, {map});
}
