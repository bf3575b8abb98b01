// Cards: round trip, validation with keys named, and FE exports with their refusals.
#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include <cstdio>
#include <fstream>

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

TEST(Export, AnsysAndLsDynaCarryTheSameSeries) {
  const auto c = prony_card(2);
  const auto ansys = card::export_card(c, "ansys");
  EXPECT_NE(ansys.find("TB,PRONY,1,,2,SHEAR\nTBDATA,1,0.3333333333,0.1,0.5,1\n"), std::string::npos) << ansys;
  const auto dyna = card::export_card(c, "lsdyna");
  // Long-term shear modulus as a term with beta = 0, then G_i with beta_i = 1/tau_i.
  EXPECT_NE(dyna.find("1,0.0,0.0,0.0\n2,10,0,0\n3,1,0,0\n"), std::string::npos) << dyna;
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
