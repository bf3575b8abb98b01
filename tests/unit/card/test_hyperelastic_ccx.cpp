// CalculiX as the independent FE code for hyperelastic exports (docs/hyperelastic.md §"Checked in
// CalculiX"): a card fitted to Treloar's data for every law CalculiX reads, exported by fitlib's
// Abaqus writer, run as one C3D8 element under NLGEOM in uniaxial tension and compression,
// equibiaxial and planar tension; the nominal stress (total reaction force over the undeformed
// unit area) agrees with the card's within 0.5 %. Runs only when ccx is installed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "common/temp_path.hpp"
#include "fitlib/card/hyperelastic.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"

using namespace fitlib;
using model::DeformationMode;

namespace {

bool have_ccx() { return std::system("command -v ccx > /dev/null 2>&1") == 0; }

// Unit cube, symmetry planes x = 0, y = 0, z = 0; x = 1 moved to the stretch; y = 1 moved too
// (equibiaxial) or held (planar); the reaction on x = 1 is P11 · 1 mm².
std::string deck(const std::string& material, const std::string& name, DeformationMode mode, double stretch) {
  std::ostringstream d;
  d << "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
    << "*ELEMENT, TYPE=C3D8, ELSET=E\n1,1,2,3,4,5,6,7,8\n"
    << "*NSET, NSET=X0\n1,4,5,8\n*NSET, NSET=X1\n2,3,6,7\n*NSET, NSET=Y0\n1,2,5,6\n*NSET, NSET=Y1\n3,4,7,8\n"
    << "*NSET, NSET=Z0\n1,2,3,4\n"
    << material << "*SOLID SECTION, ELSET=E, MATERIAL=" << name << "\n"
    << "*BOUNDARY\nX0,1,1,0\nY0,2,2,0\nZ0,3,3,0\n";
  if (mode == DeformationMode::planar) d << "Y1,2,2,0\n";
  d << "*STEP, NLGEOM, INC=1000\n*STATIC\n0.05,1.0\n*BOUNDARY\nX1,1,1," << stretch - 1.0 << "\n";
  if (mode == DeformationMode::equibiaxial) d << "Y1,2,2," << stretch - 1.0 << "\n";
  d << "*NODE PRINT, NSET=X1, TOTALS=ONLY\nRF\n*END STEP\n";
  return d.str();
}

// The last total x force of set X1 in a .dat file.
double last_total_fx(const std::string& dat) {
  const auto at = dat.rfind("total force (fx,fy,fz) for set X1");
  if (at == std::string::npos) throw core::NumericalError("no total force in the .dat");
  std::istringstream rest(dat.substr(dat.find('\n', at)));
  double fx = NAN;
  rest >> fx;
  return fx;
}

double ccx_nominal_stress(const std::string& material, const std::string& name, DeformationMode mode, double stretch,
                          const std::string& job) {
  const std::string dir = fitlib_test::temp_path("ccx-" + job);
  std::filesystem::create_directories(dir);
  core::write_file_atomically(dir + "/" + job + ".inp", deck(material, name, mode, stretch));
  const std::string cmd = "cd '" + dir + "' && ccx -i " + job + " > " + job + ".log 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << "ccx failed, see " << dir;
  return last_total_fx(core::read_file(dir + "/" + job + ".dat"));
}

std::vector<card::ParameterEstimate> estimates(std::initializer_list<double> values) {
  std::vector<card::ParameterEstimate> out;
  for (double v : values) {
    card::ParameterEstimate e;
    e.value = v;
    out.push_back(e);
  }
  return out;
}

// A card of law `kind` with its model's resolved options and the given parameter values.
card::Card law_card(const std::string& name, const std::string& kind, const nlohmann::json& options,
                    std::initializer_list<double> values) {
  card::Card c;
  c.name = name, c.model_kind = kind, c.model_options = model::make_model(kind, options)->options();
  c.parameters = estimates(values);
  return c;
}

}  // namespace

TEST(HyperelasticCalculix, EveryExportedLawGivesTheCardsStressInOneElement) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  const auto table =
      data::read_quasi_static_table(std::string(FITLIB_SOURCE_DIR) + "/datasets/materials/treloar1944-czhao.csv");
  const std::vector<std::pair<std::string, nlohmann::json>> laws = {
      {"neo-hooke", {}},          {"mooney-rivlin", {{"terms", 2}}}, {"mooney-rivlin", {{"terms", 3}}},
      {"yeoh", {}},               {"reduced-polynomial", {{"terms", 2}}}, {"ogden", {{"terms", 1}}},
      {"ogden", {{"terms", 2}}}, {"ogden", {{"terms", 3}}},         {"arruda-boyce", {}}};
  const std::vector<std::pair<DeformationMode, double>> loads = {{DeformationMode::uniaxial, 2.0},
                                                                 {DeformationMode::uniaxial, 0.8},
                                                                 {DeformationMode::equibiaxial, 1.8},
                                                                 {DeformationMode::planar, 2.0}};
  int job = 0;
  for (const auto& [kind, options] : laws) {
    card::HyperelasticCardOptions o;
    o.model = kind, o.model_options = options, o.name = "TRELOAR";
    const card::Card c = card::fit_hyperelastic_card(table, o).card;
    card::ExportOptions e;
    e.poisson_ratio = 0.4999;  // K ≈ 5000 μ0: the card is incompressible
    const std::string material = card::export_hyperelastic(c, "abaqus", e);
    const auto p = c.values();
    for (const auto& [mode, stretch] : loads) {
      const double expect = c.model()->hyperelastic()->nominal_stress(p.data(), mode, stretch);
      const double got = ccx_nominal_stress(material, "TRELOAR", mode, stretch, "j" + std::to_string(job++));
      std::printf("ccx %-18s %-10s %-11s stretch %.2f: card %.6f MPa, ccx %.6f MPa (%+.3f %%)\n", kind.c_str(),
                  options.dump().c_str(), model::to_string(mode), stretch, expect, got, 100 * (got / expect - 1));
      EXPECT_NEAR(got, expect, 0.005 * std::abs(expect)) << kind << " " << options.dump() << " " << model::to_string(mode);
    }
  }
}

TEST(HyperelasticCalculix, CompressibleCardKeepsItsD1) {
  // A compressible card's D1 enters the deck as fitted; ccx's uniaxial stress still matches the
  // card's incompressible evaluation when K ≫ μ0 (docs/decisions.md "Hyperelastic: deviatoric and
  // volumetric fitted apart").
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  const card::Card c = law_card("NH", "neo-hooke", {{"compressible", true}}, {0.2, 2.0 / 2000.0});
  const std::string material = card::export_hyperelastic(c, "abaqus", {});
  EXPECT_NE(material.find("0.2,0.001\n"), std::string::npos) << material;
  const double expect = c.model()->hyperelastic()->nominal_stress(c.values().data(), DeformationMode::uniaxial, 1.5);
  EXPECT_NEAR(ccx_nominal_stress(material, "NH", DeformationMode::uniaxial, 1.5, "nh"), expect, 0.005 * expect);
}

TEST(HyperelasticExport, ConventionsPerCode) {
  // Ogden: Abaqus μ_i as in the card; ANSYS and LS-DYNA 2 μ_i/α_i; Gent has no Abaqus form.
  const card::Card c = law_card("OG", "ogden", {{"terms", 1}}, {0.4, 2.0});
  card::ExportOptions e;
  e.density_t_per_mm3 = 1.2e-9;
  EXPECT_NE(card::export_hyperelastic(c, "abaqus", e).find("*HYPERELASTIC, OGDEN, N=1\n0.4,2,"), std::string::npos);
  EXPECT_NE(card::export_hyperelastic(c, "ansys", e).find("TB,HYPER,1,,1,OGDEN\nTBDATA,1,0.4,2,"), std::string::npos);
  const std::string dyna = card::export_hyperelastic(c, "lsdyna", e);
  EXPECT_NE(dyna.find("*MAT_OGDEN_RUBBER"), std::string::npos);
  EXPECT_NE(dyna.find("\n0.4,0,0,0,0,0,0,0\n$ ALPHA1 ... ALPHA8\n2,0,0,0,0,0,0,0\n"), std::string::npos) << dyna;
  card::Card g = c;
  g.model_kind = "gent", g.model_options = {{"compressible", false}}, g.parameters = estimates({0.3, 90.0});
  EXPECT_THROW(card::export_hyperelastic(g, "abaqus", e), core::UsageError);
  EXPECT_NE(card::export_hyperelastic(g, "ansys", e).find("TB,HYPER,1,,,GENT\nTBDATA,1,0.3,90,"), std::string::npos);
}

TEST(HyperelasticExport, ViscoHyperelasticCardCombinesABaseAndAPronyCard) {
  const card::Card base = law_card("OG", "ogden", {{"terms", 1}}, {0.4, 2.0});
  card::Card prony;
  prony.name = "P", prony.model_kind = "prony", prony.model_options = {{"terms", 2}};
  const auto pm = prony.model();
  std::vector<double> pv = pm->default_parameters();
  // G_inf, G_1, G_2, tau_1, tau_2 in the prony model's order
  std::vector<std::string> names;
  for (const auto& s : pm->parameters()) names.push_back(s.name);
  ASSERT_EQ(names, (std::vector<std::string>{"G_inf", "G_1", "G_2", "tau_1", "tau_2"}));
  prony.parameters = estimates({2.0, 1.0, 1.0, 0.01, 1.0});
  const card::Card c = card::visco_hyperelastic_card(base, prony, "VH");
  EXPECT_EQ(c.values(), (std::vector<double>{0.4, 2.0, 0.25, 0.25, 0.01, 1.0}));
  const card::Card back = card::card_from_json(card::card_to_json(c));
  EXPECT_EQ(back.values(), c.values());
  const std::string deck = card::export_card(back, "abaqus");
  EXPECT_NE(deck.find("*HYPERELASTIC, OGDEN, N=1, MODULI=LONG TERM\n0.4,2,"), std::string::npos) << deck;
  EXPECT_NE(deck.find("*VISCOELASTIC, TIME=PRONY\n0.25,0,0.01\n0.25,0,1\n"), std::string::npos) << deck;
  EXPECT_THROW(card::export_card(back, "ansys"), core::UsageError);
  EXPECT_THROW(card::visco_hyperelastic_card(prony, prony, "X"), core::UsageError);
}
