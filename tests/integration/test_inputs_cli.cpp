// fitcli on pyvisco's inputs: EPLEXOR .xls, relaxation tables, shift files, eval --time-s, plot.
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace {

std::string material(const std::string& name) { return source_path("datasets/materials/" + name); }
std::string unique(const std::string& name) { return temp_file(std::to_string(getpid()) + "-" + name); }

TEST(InputsCli, EplexorXlsIsRecognisedByContent) {
  const auto out = unique("eplexor.json");
  const auto r = run_fitcli("fit --data " + material("pyvisco-eplexor-master.xls") +
                            " --model prony --terms 8 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("EPLEXOR master export, Ref.Temp. 25 degC"), std::string::npos) << r.err;
  const auto card = nlohmann::json::parse(slurp(out));
  EXPECT_EQ(card["options"]["mode"], "uniaxial");
  EXPECT_EQ(card["fit"]["n_points"], 210);
}

TEST(InputsCli, BadXlsCellExitsThreeNamingSheetRowColumn) {
  const auto r = run_fitcli("fit --data " + std::string(FITLIB_TEST_DATA_DIR) +
                            "/eplexor/negative_storage.xls --model prony --terms 4");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("negative_storage.xls:4:13: sheet 'Exported Data', column M"), std::string::npos) << r.err;
}

TEST(InputsCli, RelaxationMasterFitAndEvalTimeReproduceTheData) {
  const auto out = unique("relax.json");
  const auto r = run_fitcli("fit --data " + material("pyvisco-time-master.csv") +
                            " --format pyvisco --model prony --terms 26 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("backend nnls+ceres"), std::string::npos);
  const auto e = run_fitcli("eval --card " + out + " --mode uniaxial --time-s 0.00281764,1e28 --json");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto rows = nlohmann::json::parse(e.out)["rows"];
  EXPECT_NEAR(rows[0]["relaxation_modulus_MPa"].get<double>(), 1714.266, 0.02 * 1714.266);
  // J(t)·E(t) ≤ 1 for a viscoelastic solid (equality in the elastic limit), and close to 1 here.
  for (const auto& row : rows)
    EXPECT_GE(row["creep_compliance_per_MPa"].get<double>() * row["relaxation_modulus_MPa"].get<double>(),
              0.9);
  for (const auto& row : rows)
    EXPECT_LE(row["creep_compliance_per_MPa"].get<double>() * row["relaxation_modulus_MPa"].get<double>(),
              1.0 + 1e-12);
}

TEST(InputsCli, RelaxationIsothermsWithGivenShiftsGetAPolynomialLaw) {
  const auto out = unique("relax-raw.json");
  const auto r = run_fitcli("fit --data " + material("pyvisco-time-raw.csv") + " --format pyvisco --model prony"
                            " --terms 12 --shifts " + material("pyvisco-time-raw-shift-factors.csv") +
                            " --reference-c 3 --temperature-law polynomial --polynomial-degree 4 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto card = nlohmann::json::parse(slurp(out));
  EXPECT_EQ(card["temperature"]["law"], "polynomial");
  EXPECT_EQ(card["temperature"]["coefficients"].size(), 4u);
  EXPECT_EQ(card["options"]["polynomial_degree"], 4);
}

TEST(InputsCli, GivenShiftsAreWrittenBackInPyviscosFormat) {
  const auto shifts = unique("shifts.csv"), out = unique("given.json");
  const auto r = run_fitcli("fit --data " + material("pyvisco-freq-raw.csv") + " --format pyvisco --model prony"
                            " --terms 10 --shifts " + material("pyvisco-freq-master-shift-factors.csv") +
                            " --reference-c -5 --shifts-out " + shifts + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto text = slurp(shifts);
  EXPECT_EQ(text.rfind("T,log_aT\nC,-\n", 0), 0u);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 23);
}

TEST(InputsCli, EvalNeedsFrequencyOrTime) {
  const auto r = run_fitcli("eval --card " + source_path("datasets/cards/synthetic-prony-shear-true.json"));
  EXPECT_EQ(r.exit_code, 2);
}

TEST(InputsCli, PlotWritesTheSamePngTwice) {
  const auto a = unique("a.png"), b = unique("b.png");
  const std::string args = "plot --data " + material("synthetic-prony-wlf.csv") + " --card " +
                           source_path("datasets/cards/synthetic-prony-wlf-true.json") + " --out ";
  const auto r1 = run_fitcli(args + a);
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  ASSERT_EQ(run_fitcli(args + b).exit_code, 0);
  const auto png = slurp(a);
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(png, slurp(b));
}

TEST(InputsCli, PlotWithoutGnuplotExitsFive) {  // README "Exit codes"
  const std::string cmd = "PATH=/nonexistent " + std::string(FITCLI_EXE) + " plot --data " +
                          material("synthetic-prony-wlf.csv") + " --card " +
                          source_path("datasets/cards/synthetic-prony-wlf-true.json") + " --out " + unique("x.png") +
                          " 2>" + unique("err.txt");
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 5);
  EXPECT_NE(slurp(unique("err.txt")).find("gnuplot is not on PATH"), std::string::npos);
}

}  // namespace
