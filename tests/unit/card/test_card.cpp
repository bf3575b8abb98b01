// Cards: round trip, validation with keys named, and FE exports with their refusals.
#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "fitlib/card/card.hpp"
#include "fitlib/card/export.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"

using namespace fitlib;

namespace {

card::Card prony_card(int terms, nlohmann::json extra = nlohmann::json::object()) {
  card::Card c;
  c.name = "test-rubber";
  c.model_kind = "prony";
  c.model_options = {{"terms", terms}, {"mode", "shear"}};
  c.model_options.update(extra);
  const auto m = c.model();
  for (size_t i = 0; i < m->size(); ++i) {
    card::ParameterEstimate e;
    const auto& name = m->parameters()[i].name;
    e.value = name.rfind("tau_", 0) == 0 ? std::pow(10.0, double(i) - 2.0 * terms) : 1.0 + i;
    if (name == "C1") e.value = 8.86;
    if (name == "C2") e.value = 101.6;
    e.std_error = 0.01 * e.value;
    e.ci95_low = 0.98 * e.value;
    e.ci95_high = 1.02 * e.value;
    c.parameters.push_back(e);
  }
  c.fit = {{"backend", "nnls"}, {"n_points", 10}};
  c.provenance = {{"data_sha256", "abc"}};
  return c;
}

std::string temp_path(const std::string& name) { return fitlib_test::temp_path(name); }

}  // namespace

TEST(Card, SaveLoadRoundTripIsExactAndDeterministic) {
  const auto c = prony_card(3, {{"temperature_law", "wlf"}, {"reference_C", -5.0}});
  const auto path = temp_path("card.json");
  card::save_card(path, c);
  const auto first = core::read_file(path);
  const auto back = card::load_card(path);
  ASSERT_EQ(back.parameters.size(), c.parameters.size());
  for (size_t i = 0; i < c.parameters.size(); ++i) {
    EXPECT_EQ(back.parameters[i].value, c.parameters[i].value);  // bit-exact
    EXPECT_EQ(*back.parameters[i].std_error, *c.parameters[i].std_error);
  }
  card::save_card(path, back);
  EXPECT_EQ(core::read_file(path), first);
  const auto j = nlohmann::json::parse(first);
  EXPECT_EQ(j["schema"], "fitlib.card/1");
  EXPECT_EQ(j["temperature"]["law"], "wlf");
  EXPECT_EQ(j["temperature"]["C1"], 8.86);
}

TEST(Card, UnestimableStandardErrorIsNullWithAReason) {
  auto c = prony_card(1);
  c.parameters[1].std_error.reset();
  c.parameters[1].std_error_reason = "rank-deficient Jacobian";
  const auto j = card::card_to_json(c);
  EXPECT_TRUE(j["parameters"][1]["std_error"].is_null());
  EXPECT_EQ(j["parameters"][1]["std_error_reason"], "rank-deficient Jacobian");
}

TEST(Card, ValidationNamesTheKey) {
  auto j = card::card_to_json(prony_card(2));
  auto expect_key = [](const nlohmann::json& bad, const std::string& key) {
    try {
      card::card_from_json(bad, "c.json");
      ADD_FAILURE() << "no error for " << key;
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.key(), key) << e.what();
      EXPECT_EQ(e.file(), "c.json");
    }
  };
  auto bad = j;
  bad["schema"] = "other/9";
  expect_key(bad, "schema");
  bad = j;
  bad["parameters"][3]["name"] = "tau_9";
  expect_key(bad, "parameters[3].name");
  bad = j;
  bad["parameters"][3]["value"] = -1.0;  // a relaxation time must be positive
  expect_key(bad, "parameters[3].value");
  bad = j;
  bad["options"]["terms"] = 3;  // parameter count no longer matches
  expect_key(bad, "parameters");
  bad = j;
  bad["options"]["bogus"] = 1;
  expect_key(bad, "options");
  bad = j;
  bad.erase("model");
  expect_key(bad, "model");
}

TEST(Card, InvalidJsonReportsLineAndColumn) {
  const auto path = temp_path("broken.json");
  std::ofstream(path) << "{\n  \"schema\": \"fitlib.card/1\",\n  \"name\": oops\n}\n";
  try {
    card::load_card(path);
    FAIL();
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_GT(e.column(), 9);
  }
}

TEST(Export, AbaqusPronyWeightsSumWithLongTermToOne) {
  const auto c = prony_card(2, {{"temperature_law", "wlf"}, {"reference_C", -5.0}});
  const auto text = card::export_card(c, "abaqus");
  // G_inf = 1, G_1 = 2, G_2 = 3, tau = 0.1, 1 s → g = 2/6, 3/6.
  EXPECT_NE(text.find("*VISCOELASTIC, TIME=PRONY\n0.3333333333, 0, 0.1\n0.5, 0, 1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("*TRS, DEFINITION=WLF\n-5, 8.86, 101.6\n"), std::string::npos) << text;
}

// A retardation spectrum is exported through its exact Maxwell series: the Abaqus deck's numbers,
// read back as G*(ω) = G_0 (1 − Σ g_i + Σ g_i iωτ_i/(1 + iωτ_i)) with G_0 = E_0/(2(1 + ν)), are
// the card's 1/J*(ω) (closed form from J_g, L_i, λ_i) to 1e-8 over six decades.
TEST(Export, RetardationCardGoesOutAsItsExactPronySeries) {
  card::Card c;
  c.name = "ret";
  c.model_kind = "retardation";
  c.model_options = {{"terms", 2}, {"mode", "shear"}};
  const double Jg = 0.25, L[2] = {0.1, 0.3}, lambda[2] = {0.01, 1.0};
  for (double v : {Jg, L[0], L[1], lambda[0], lambda[1]}) c.parameters.push_back(card::ParameterEstimate{v, false, {}, {}, {}, {}});
  const std::string deck = card::export_card(c, "abaqus");
  std::string header = deck.substr(0, deck.find("*MATERIAL"));  // comment lines of <= 80 characters, joined
  for (std::size_t at; (at = header.find("\n** ")) != std::string::npos;) header.replace(at, 4, " ");
  EXPECT_NE(header.find("2 Prony terms converted exactly from its retardation spectrum"), std::string::npos) << deck;
  std::stringstream in(deck.substr(deck.find("*ELASTIC")));
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  const double E0 = std::stod(line), nu = std::stod(line.substr(line.find(',') + 1));
  std::getline(in, line);  // *VISCOELASTIC
  std::vector<std::pair<double, double>> terms;  // g_i, tau_i
  while (std::getline(in, line) && line[0] != '*') {
    const double g = std::stod(line), tau = std::stod(line.substr(line.rfind(',') + 1));
    terms.emplace_back(g, tau);
  }
  ASSERT_EQ(terms.size(), 2u);
  const double G0 = E0 / (2.0 * (1.0 + nu));
  EXPECT_NEAR(G0, 1.0 / Jg, 1e-8);
  const std::complex<double> i(0.0, 1.0);
  for (double f = 1e-3; f <= 1e3; f *= 10.0) {
    const double w = 2.0 * M_PI * f;
    std::complex<double> J = Jg, G = 1.0;
    for (int k = 0; k < 2; ++k) J += L[k] / (1.0 + i * w * lambda[k]);
    for (const auto& [g, tau] : terms) G += g * (i * w * tau / (1.0 + i * w * tau) - 1.0);
    G *= G0;
    EXPECT_NEAR(std::abs(G - 1.0 / J) / std::abs(1.0 / J), 0.0, 1e-8) << f << " Hz";
  }
  // Its fit's ceiling on 1/J_g holds at the export: 4 MPa passes 10 MPa, not 1 MPa.
  c.fit["admissible"] = {{"tau_min_s", 1e-3}, {"tau_max_s", 1e3}, {"glassy_modulus_max_MPa", 10.0}};
  EXPECT_EQ(card::admissibility_problems(c), "");
  c.fit["admissible"]["glassy_modulus_max_MPa"] = 1.0;
  EXPECT_NE(card::admissibility_problems(c).find("instantaneous modulus 4 MPa above 1 MPa"), std::string::npos)
      << card::admissibility_problems(c);
  EXPECT_THROW(card::export_card(c, "abaqus"), core::UsageError);
}

TEST(Export, AnsysAndLsDynaCarryTheSameSeries) {
  const auto c = prony_card(2);
  const auto ansys = card::export_card(c, "ansys");
  EXPECT_NE(ansys.find("TB,PRONY,1,,2,SHEAR\nTBDATA,1,0.3333333333,0.1,0.5,1\n"), std::string::npos) << ansys;
  card::ExportOptions with_density;
  with_density.density_t_per_mm3 = 1.2e-9;
  const auto dyna = card::export_card(c, "lsdyna", with_density);
  // Long-term shear modulus as a term with beta = 0, then G_i with beta_i = 1/tau_i.
  EXPECT_NE(dyna.find("1,0.0,0,0.0\n2,10,0,0\n3,1,0,0\n"), std::string::npos) << dyna;
}

namespace {

// The moduli an LS-DYNA *MAT_GENERAL_VISCOELASTIC deck stands for, read back from its numbers by
// the convention docs/formats.md §3 states: G(t) = Σ GI e^(−BETAI t); K(t) = Σ KI e^(−BETAKI t)
// when a KI is non-zero, else K = BULK. An independent reader of the written text.
struct DynaModuli {
  double ro = 0.0, bulk = 0.0, shear0 = 0.0, shear_inf = 0.0, bulk0 = 0.0, bulk_inf = 0.0;
};

std::vector<double> fields_of(const std::string& line) {
  std::vector<double> v;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) v.push_back(std::stod(field));
  return v;
}

DynaModuli read_back(const std::string& deck) {
  std::stringstream in(deck.substr(deck.find("*MAT_GENERAL_VISCOELASTIC")));
  std::string line;
  std::vector<std::vector<double>> rows;
  std::getline(in, line);  // the keyword
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '$') rows.push_back(fields_of(line));
  DynaModuli m;
  m.ro = rows.at(0).at(1);
  m.bulk = rows.at(0).at(2);
  bool bulk_series = false;
  for (std::size_t r = 2; r < rows.size(); ++r) {  // GI, BETAI, KI, BETAKI
    const auto& g = rows[r];
    m.shear0 += g.at(0);
    if (g.at(1) == 0.0) m.shear_inf += g.at(0);
    m.bulk0 += g.at(2);
    if (g.at(3) == 0.0) m.bulk_inf += g.at(2);
    bulk_series = bulk_series || g.at(2) != 0.0;
  }
  if (!bulk_series) m.bulk0 = m.bulk_inf = m.bulk;
  return m;
}

}  // namespace

// Issue 9: the deck's instantaneous and long-time shear and bulk moduli, recomputed from the
// written numbers, are the card's (closed forms from its series and the Poisson ratio 0.4995).
TEST(Export, LsDynaDeckHoldsTheCardsModuliAndDensity) {
  card::ExportOptions o;
  o.density_t_per_mm3 = 1.15e-9;
  const double nu = o.poisson_ratio, rel = 1e-9;
  // Shear card: G_inf = 1, G_1 = 2, G_2 = 3 MPa; bulk elastic, K = 2 G0 (1 + nu)/(3 (1 − 2 nu)).
  const DynaModuli s = read_back(card::export_card(prony_card(2), "lsdyna", o));
  EXPECT_EQ(s.ro, 1.15e-9);
  EXPECT_NEAR(s.shear0, 6.0, rel * 6.0);
  EXPECT_NEAR(s.shear_inf, 1.0, rel);
  const double k_shear_card = 2.0 * 6.0 * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
  EXPECT_NEAR(s.bulk0, k_shear_card, rel * k_shear_card);
  EXPECT_NEAR(s.bulk_inf, k_shear_card, rel * k_shear_card);
  // Uniaxial card: E0 = 6, E_inf = 1 MPa; K0 = E0/(3(1 − 2 nu)), G0 = 3 K0 E0/(9 K0 − E0), and
  // both relax by the same fraction E_inf/E0 (constant Poisson ratio).
  const DynaModuli u = read_back(card::export_card(prony_card(2, {{"mode", "uniaxial"}}), "lsdyna", o));
  const double k0 = 6.0 / (3.0 * (1.0 - 2.0 * nu)), g0 = 3.0 * k0 * 6.0 / (9.0 * k0 - 6.0);
  EXPECT_NEAR(u.bulk, k0, rel * k0);  // BULK is K(0)
  EXPECT_NEAR(u.bulk0, k0, 1e-8 * k0);
  EXPECT_NEAR(u.bulk_inf, k0 / 6.0, 1e-8 * k0);
  EXPECT_NEAR(u.shear0, g0, 1e-8 * g0);
  EXPECT_NEAR(u.shear_inf, g0 / 6.0, 1e-8 * g0);
}

TEST(Export, LsDynaRefusesWithoutADensity) {
  try {
    card::export_card(prony_card(2), "lsdyna");
    FAIL() << "exported with RO = 0";
  } catch (const core::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--density"), std::string::npos) << e.what();
  }
}

// A deck at one temperature (--temperature-c) for laws the solvers lack: the Abaqus numbers read back
// as G(t) = G_0 (1 − Σ g_i (1 − e^(−t/τ_i))), G_0 = E_0/(2(1 + ν)), are the card's own G(t, T)
// (Model::relaxation_modulus at T) to 1e-9 over eight decades — Arrhenius, a quadratic polynomial
// and WLF with the entropic factor T/T_ref —, with no *TRS; the refusal without it names the route.
TEST(Export, AtOneTemperatureTheDeckHoldsTheCardsRelaxationThereForAnyLaw) {
  const std::vector<std::pair<nlohmann::json, std::vector<double>>> laws = {
      {{{"temperature_law", "arrhenius"}}, {80.0}},
      {{{"temperature_law", "polynomial"}, {"polynomial_degree", 2}}, {-0.12, 4e-4}},
      {{{"temperature_law", "wlf"}, {"vertical_shift", true}}, {8.86, 101.6}}};
  const double T = 61.5;
  for (const auto& [options, law] : laws) {
    auto c = prony_card(3, options);
    c.model_options["reference_C"] = 23.0;
    const auto m = c.model();
    const std::size_t first = m->size() - law.size();
    for (std::size_t k = 0; k < law.size(); ++k) c.parameters[first + k].value = law[k];
    if (options["temperature_law"] != "wlf")  // Abaqus holds WLF without a vertical shift only
      EXPECT_THROW(
          try { card::export_card(c, "abaqus"); } catch (const core::UsageError& e) {
            EXPECT_NE(std::string(e.what()).find("--temperature-c T"), std::string::npos) << e.what();
            throw;
          },
          core::UsageError);
    card::ExportOptions o;
    o.temperature_C = T;
    const std::string deck = card::export_card(c, "abaqus", o);
    EXPECT_EQ(deck.find("*TRS"), std::string::npos) << deck;
    EXPECT_NE(deck.find("at 61.5 degC only"), std::string::npos) << deck;
    std::istringstream in(deck.substr(deck.find("*ELASTIC, MODULI=INSTANTANEOUS\n") + 31));
    double E0 = 0.0, nu = 0.0;
    char comma = 0;
    in >> E0 >> comma >> nu;
    std::vector<double> g, tau;
    std::string line;
    std::getline(in, line), std::getline(in, line);  // the rest of the *ELASTIC line, *VISCOELASTIC
    while (std::getline(in, line) && !line.empty() && line[0] != '*') {
      std::istringstream row(line);
      double gi = 0.0, ki = 0.0, ti = 0.0;
      row >> gi >> comma >> ki >> comma >> ti;
      g.push_back(gi), tau.push_back(ti);
    }
    ASSERT_EQ(g.size(), 3u) << deck;
    const double G0 = E0 / (2.0 * (1.0 + nu));
    model::TestCondition at;
    at.mode = model::TestMode::shear;
    at.temperature_C = T;
    for (double t = 1e-10; t < 1e-1; t *= 10.0) {
      double G = G0;
      for (std::size_t i = 0; i < g.size(); ++i) G -= G0 * g[i] * (1.0 - std::exp(-t / tau[i]));
      const double card_G = m->relaxation_modulus(c.values().data(), at, t);
      EXPECT_NEAR(G, card_G, 1e-9 * card_G) << options.dump() << " t = " << t;
    }
  }
  // A temperature where the law describes no material (at the WLF pole) is refused.
  card::ExportOptions pole;
  pole.temperature_C = 23.0 - 101.6;
  EXPECT_THROW(card::export_card(prony_card(2, {{"temperature_law", "wlf"}, {"reference_C", 23.0}}), "abaqus", pole),
               core::InputError);
}

TEST(Export, RefusesWhatAFormatCannotHold) {
  EXPECT_THROW(card::export_card(prony_card(6), "lsdyna"), core::UsageError);  // > 5 terms
  EXPECT_THROW(card::export_card(prony_card(2), "calculix"), core::UsageError);
  EXPECT_THROW(card::export_card(prony_card(2, {{"temperature_law", "arrhenius"}}), "abaqus"), core::UsageError);
  // The polynomial law is typed as such (Model::temperature_law_info), not dropped silently.
  EXPECT_THROW(card::export_card(prony_card(2, {{"temperature_law", "polynomial"}, {"polynomial_degree", 1}}), "abaqus"),
               core::UsageError);
  card::Card frac;
  frac.model_kind = "fractional-zener";
  for (double v : {1.0, 10.0, 0.1, 0.5}) frac.parameters.push_back(card::ParameterEstimate{v, false, {}, {}, {}, {}});
  EXPECT_THROW(card::export_card(frac, "abaqus"), core::UsageError);
  card::Card z;  // tau_eps < tau_T: negative Prony weight
  z.model_kind = "zener3";
  for (double v : {100.0, 0.5, 0.2}) z.parameters.push_back(card::ParameterEstimate{v, false, {}, {}, {}, {}});
  EXPECT_THROW(card::export_card(z, "ansys"), core::UsageError);
}
