// fitcli's hyperelastic round trip (docs/hyperelastic.md): fit → card → eval → export → CalculiX for
// every law, the figure, and the bad-input exits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"

namespace {

const std::string kTreloar = source_path("datasets/materials/treloar1944-czhao.csv");

// One C3D8 element in uniaxial tension to `stretch` with the exported material; ccx's nominal
// stress (total reaction on x = 1 over the unit area).
double ccx_uniaxial(const std::string& keywords, double stretch, const std::string& job) {
  const std::string dir = temp_file("ccx-" + job);
  std::filesystem::create_directories(dir);
  std::ostringstream d;
  d << "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
    << "*ELEMENT, TYPE=C3D8, ELSET=E\n1,1,2,3,4,5,6,7,8\n*NSET, NSET=X0\n1,4,5,8\n*NSET, NSET=X1\n2,3,6,7\n"
    << "*NSET, NSET=Y0\n1,2,5,6\n*NSET, NSET=Z0\n1,2,3,4\n"
    << keywords << "*SOLID SECTION, ELSET=E, MATERIAL=RT\n*BOUNDARY\nX0,1,1,0\nY0,2,2,0\nZ0,3,3,0\n"
    << "*STEP, NLGEOM, INC=1000\n*STATIC\n0.05,1.0\n*BOUNDARY\nX1,1,1," << stretch - 1.0
    << "\n*NODE PRINT, NSET=X1, TOTALS=ONLY\nRF\n*END STEP\n";
  std::ofstream(dir + "/" + job + ".inp") << d.str();
  EXPECT_EQ(std::system(("cd '" + dir + "' && ccx -i " + job + " > log 2>&1").c_str()), 0);
  const std::string dat = slurp(dir + "/" + job + ".dat");
  std::istringstream rest(dat.substr(dat.find('\n', dat.rfind("total force"))));
  double fx = NAN;
  rest >> fx;
  return fx;
}

}  // namespace

TEST(HyperelasticCli, FitEvalExportCalculixRoundTripForEveryLaw) {
  const bool ccx = std::system("command -v ccx > /dev/null 2>&1") == 0;
  const std::vector<std::string> laws = {"neo-hooke", "mooney-rivlin --terms 3", "yeoh", "reduced-polynomial --terms 2",
                                         "ogden --terms 3", "arruda-boyce", "gent"};
  int k = 0;
  for (const auto& law : laws) {
    const std::string card = temp_file("rt" + std::to_string(k) + ".json");
    const auto fit = run_fitcli("fit --data " + kTreloar + " --model " + law + " --name RT --out " + card);
    ASSERT_EQ(fit.exit_code, 0) << law << "\n" << fit.err;
    EXPECT_NE(fit.out.find("uniaxial (24 points): rms relative error"), std::string::npos) << fit.out;
    const auto eval = run_fitcli("eval --card " + card + " --mode uniaxial --stretch 1.5,2");
    ASSERT_EQ(eval.exit_code, 0) << eval.err;
    EXPECT_EQ(eval.out.substr(0, eval.out.find('\n')), "mode,stretch,nominal_stress_MPa,cauchy_stress_MPa");
    std::istringstream rows(eval.out);
    std::string line;
    std::getline(rows, line), std::getline(rows, line), std::getline(rows, line);  // the row at stretch 2
    const double P = std::stod(line.substr(line.find(',', line.find(',') + 1) + 1));
    const double sigma = std::stod(line.substr(line.rfind(',') + 1));
    EXPECT_NEAR(sigma, 2.0 * P, 1e-12 * sigma) << line;
    const auto abaqus = run_fitcli("export --card " + card + " --format abaqus --poisson-ratio 0.4999");
    if (law == "gent") {  // no Abaqus form: refused, and ANSYS takes it
      EXPECT_EQ(abaqus.exit_code, 2) << abaqus.err;
      EXPECT_NE(abaqus.err.find("no Gent form"), std::string::npos) << abaqus.err;
      EXPECT_EQ(run_fitcli("export --card " + card + " --format ansys").exit_code, 0);
      continue;
    }
    ASSERT_EQ(abaqus.exit_code, 0) << abaqus.err;
    if (ccx) EXPECT_NEAR(ccx_uniaxial(abaqus.out, 2.0, "rt" + std::to_string(k)), P, 0.005 * P) << law;
    ++k;
  }
}

TEST(HyperelasticCli, PlotWritesAPng) {
  const std::string card = temp_file("plot.json"), png = temp_file("plot.png");
  ASSERT_EQ(run_fitcli("fit --data " + kTreloar + " --model ogden --terms 3 --out " + card + " --plot " + png).exit_code, 0);
  const std::string bytes = slurp(png);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_EQ(run_fitcli("plot --card " + card + " --data " + kTreloar + " --out " + png).exit_code, 0);
}

TEST(HyperelasticCli, RefusalsAndBadInput) {
  // Uniaxial rows alone: Mooney–Rivlin turns Drucker-unstable within them → exit 4, nothing written.
  const std::string uni = temp_file("uni.csv"), out = temp_file("refused.json");
  std::ofstream(uni) << "mode,stretch,nominal_stress_MPa\n" << [] {
    std::istringstream all(slurp(kTreloar));
    std::string line, text;
    while (std::getline(all, line))
      if (line.rfind("uniaxial", 0) == 0) text += line + "\n";
    return text;
  }();
  const auto unstable = run_fitcli("fit --data " + uni + " --model mooney-rivlin --out " + out);
  EXPECT_EQ(unstable.exit_code, 4) << unstable.err;
  EXPECT_NE(unstable.err.find("Drucker-unstable in uniaxial tension from stretch"), std::string::npos) << unstable.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  const std::string bad = temp_file("bad.csv");
  std::ofstream(bad) << "mode,stretch,nominal_stress_MPa\nuniaxial,2,0.3\nuniaxial,inf,0.4\n";
  const auto r = run_fitcli("fit --data " + bad + " --model yeoh");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("bad.csv:3:2"), std::string::npos) << r.err;
  EXPECT_EQ(run_fitcli("fit --data " + kTreloar + " --model ogden --terms 7").exit_code, 2);
  EXPECT_EQ(run_fitcli("fit --data " + kTreloar + " --model yeoh --compressible").exit_code, 3);
  EXPECT_EQ(run_fitcli("fit --data " + kTreloar + " --model yeoh --temperature-law wlf").exit_code, 2);
  const auto dynamic = run_fitcli("fit --data " + kTreloar + " --model prony --terms 2");
  EXPECT_EQ(dynamic.exit_code, 2);
  EXPECT_NE(dynamic.err.find("is a quasi-static table"), std::string::npos) << dynamic.err;
}

TEST(HyperelasticCli, ViscoCardCombinesAndExports) {
  const std::string base = temp_file("vbase.json"), prony = temp_file("vprony.json"), vh = temp_file("vh.json");
  ASSERT_EQ(run_fitcli("fit --data " + kTreloar + " --model ogden --terms 3 --out " + base).exit_code, 0);
  const auto p = run_fitcli("fit --data " + source_path("datasets/materials/synthetic-prony-shear.csv") +
                            " --model prony --terms 3 --out " + prony);
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const auto c = run_fitcli("visco-card --base " + base + " --prony " + prony + " --name VH --out " + vh);
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const auto deck = run_fitcli("export --card " + vh + " --format abaqus");
  ASSERT_EQ(deck.exit_code, 0) << deck.err;
  EXPECT_NE(deck.out.find("*HYPERELASTIC, OGDEN, N=3, MODULI=LONG TERM"), std::string::npos) << deck.out;
  EXPECT_NE(deck.out.find("*VISCOELASTIC, TIME=PRONY"), std::string::npos) << deck.out;
  EXPECT_EQ(run_fitcli("eval --card " + vh + " --stretch 2").exit_code, 0);
  EXPECT_EQ(run_fitcli("visco-card --base " + prony + " --prony " + prony).exit_code, 2);
}

// A visco-hyperelastic card (Ogden 3 on Treloar, a Prony series) as both roles of the medium drive
// at the complete level: the segment runs it through the material-point contract to finite lives,
// in equilibrium (issue 36 item 4).
TEST(HyperelasticCli, ViscoHyperelasticCardRunsTheCompleteLevel) {
  const std::string dir = temp_file("vh-life-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  ASSERT_EQ(run_fitcli("fit --data " + kTreloar + " --model ogden --terms 3 --out " + dir + "/H.json").exit_code, 0);
  ASSERT_EQ(run_fitcli("fit --data " + source_path("datasets/materials/synthetic-prony-shear.csv") +
                       " --model prony --terms 4 --out " + dir + "/P.json").exit_code, 0);
  ASSERT_EQ(run_fitcli("visco-card --base " + dir + "/H.json --prony " + dir + "/P.json --out " + dir + "/VH.json").exit_code, 0);
  std::ofstream(dir + "/vh.toml") << slurp(source_path("datasets/drives/ref-0500-medium.toml"))
                                  << "\n[belt.materials]\nbottom = \"VH.json\"\ncushion = \"VH.json\"\n"
                                  << "\n[life]\nfidelity = \"complete\"\ncycles = 1\n";
  const auto r = run_fitcli("life --scene " + dir + "/vh.toml --out-dir " + dir + "/out --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto life = nlohmann::json::parse(r.out);
  ASSERT_EQ(life["modes"].size(), 2u);
  for (const auto& mode : life["modes"]) {
    EXPECT_TRUE(std::isfinite(mode["life_cycles"].get<double>()) && mode["life_cycles"].get<double>() > 0.0) << mode.dump();
  }
  const auto& e = life["segment_equilibrium"];
  EXPECT_LT(e["equilibrium_error"].get<double>(), e["equilibrium_error_bound"].get<double>());
}
