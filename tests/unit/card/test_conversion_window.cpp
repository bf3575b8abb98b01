// card/conversion.hpp (one mode-conversion rule for eval and exports) and card/data_window.hpp
// (the box of measured conditions a card stores), against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "fitlib/card/conversion.hpp"
#include "fitlib/card/data_window.hpp"
#include "fitlib/core/error.hpp"

using namespace fitlib;

namespace {

// A two-term Prony card in `mode`: M_inf = 2, M_1 = 3 (tau 0.1 s), M_2 = 5 (tau 10 s).
card::Card two_term_card(const char* mode) {
  card::Card c;
  c.model_kind = "prony";
  c.model_options = {{"terms", 2}, {"mode", mode}};
  for (double v : {2.0, 3.0, 5.0, 0.1, 10.0}) {
    card::ParameterEstimate p;
    p.value = v;
    c.parameters.push_back(p);
  }
  return c;
}

std::complex<double> prony(double f_Hz) {
  const std::complex<double> i(0.0, 1.0);
  const double w = 2.0 * M_PI * f_Hz;
  return 2.0 + 3.0 * i * w * 0.1 / (1.0 + i * w * 0.1) + 5.0 * i * w * 10.0 / (1.0 + i * w * 10.0);
}

model::TestCondition at(model::TestMode mode, double f_Hz) {
  model::TestCondition c;
  c.mode = mode;
  c.frequency_Hz = f_Hz;
  return c;
}

}  // namespace

TEST(ModeConversion, UniaxialCardKeepsPoissonRatioConstant) {
  const auto card = two_term_card("uniaxial");
  const double nu = 0.3;
  const auto E = prony(0.7);
  const auto G = card::moduli_in_mode(*card.model(), card.values(), at(model::TestMode::shear, 0.7), nu);
  const auto K = card::moduli_in_mode(*card.model(), card.values(), at(model::TestMode::bulk, 0.7), nu);
  EXPECT_NEAR(G.storage, E.real() / (2.0 * (1.0 + nu)), 1e-12);
  EXPECT_NEAR(G.loss, E.imag() / (2.0 * (1.0 + nu)), 1e-12);
  EXPECT_NEAR(K.storage, E.real() / (3.0 * (1.0 - 2.0 * nu)), 1e-12);
  EXPECT_NEAR(K.loss, E.imag() / (3.0 * (1.0 - 2.0 * nu)), 1e-12);
}

TEST(ModeConversion, ShearCardGetsTheExportsElasticBulkModulus) {
  const auto card = two_term_card("shear");
  const double nu = 0.45, G0 = 10.0, K = 2.0 * G0 * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
  const auto e = card::elastic_constants(model::TestMode::shear, G0, std::nan(""), nu);
  EXPECT_NEAR(e.bulk_MPa, K, 1e-12);
  EXPECT_NEAR(e.poisson, nu, 1e-12);
  const auto G = prony(3.0), E = 9.0 * K * G / (3.0 * K + G);
  const auto m = card::moduli_in_mode(*card.model(), card.values(), at(model::TestMode::uniaxial, 3.0), nu);
  EXPECT_NEAR(m.storage, E.real(), 1e-12);
  EXPECT_NEAR(m.loss, E.imag(), 1e-12);
  const auto b = card::moduli_in_mode(*card.model(), card.values(), at(model::TestMode::bulk, 3.0), nu);
  EXPECT_NEAR(b.storage, K, 1e-12);
  EXPECT_EQ(b.loss, 0.0);
}

// A shear card that is not a Maxwell series converts from its glassy modulus too: a retardation
// spectrum's 1/J_g and a fractional Zener card's G_0 + ΔG (its relaxation modulus at t = 0).
TEST(ModeConversion, ShearCardsWithoutASeriesConvertFromTheirGlassyModulus) {
  const double nu = 0.4995;
  auto check = [&](const char* kind, std::vector<double> values, double glassy, int terms) {
    card::Card c;
    c.model_kind = kind;
    if (terms > 0) c.model_options = {{"terms", terms}, {"mode", "shear"}};
    for (double v : values) c.parameters.push_back(card::ParameterEstimate{v, false, {}, {}, {}, {}});
    const double K = 2.0 * glassy * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
    const auto G = c.model()->moduli(c.values().data(), at(model::TestMode::shear, 3.0));
    const std::complex<double> Gs(G.storage, G.loss), E = 9.0 * K * Gs / (3.0 * K + Gs);
    const auto m = card::moduli_in_mode(*c.model(), c.values(), at(model::TestMode::uniaxial, 3.0), nu);
    EXPECT_NEAR(m.storage / E.real(), 1.0, 1e-6) << kind;
    EXPECT_NEAR(m.loss / E.imag(), 1.0, 1e-6) << kind;
    EXPECT_NEAR(card::point_bulk_modulus_MPa(*c.model(), c.values(), at(model::TestMode::bulk, 3.0), nu) / K, 1.0,
                1e-6) << kind;
  };
  check("retardation", {0.25, 0.1, 0.3, 0.01, 1.0}, 4.0, 2);
  check("fractional-zener", {1.0, 10.0, 0.1, 0.5}, 11.0, 0);
}

TEST(ModeConversion, NativeModeIsTheModelsOwn) {
  const auto card = two_term_card("shear");
  const auto m = card::moduli_in_mode(*card.model(), card.values(), at(model::TestMode::shear, 1.0), 0.1);
  EXPECT_DOUBLE_EQ(m.storage, prony(1.0).real());
}

// Rows at 0.1 and 100 Hz, 23 and 60 °C (moduli unused).
static data::DynamicTestTable corners_0p1_100Hz_23_60C() {
  data::DynamicTestTable t;
  for (double f : {0.1, 100.0})
    for (double T : {23.0, 60.0}) {
      data::DynamicTestRow row;
      row.condition.frequency_Hz = f;
      row.condition.temperature_C = T;
      t.rows.push_back(row);
    }
  return t;
}

TEST(DataWindow, BoxOfMeasuredConditionsWithSlackAtTheBounds) {
  const data::DynamicTestTable t = corners_0p1_100Hz_23_60C();
  const auto w = card::data_window_json(t);
  EXPECT_EQ(w, (nlohmann::json{{"frequency_Hz", {0.1, 100.0}}, {"temperature_C", {23.0, 60.0}}}));  // no amplitude
  card::Card card = two_term_card("shear");
  card.fit["data_window"] = w;
  model::TestCondition c = at(model::TestMode::shear, 100.0 * (1.0 + 1e-12));
  c.temperature_C = 60.0;
  EXPECT_TRUE(card::outside_data_window(card, c).empty());
  c.temperature_C = 61.0;
  c.frequency_Hz = 0.05;
  const auto x = card::outside_data_window(card, c);
  ASSERT_EQ(x.size(), 2u);
  EXPECT_EQ(x[0].quantity, "frequency_Hz");
  EXPECT_EQ(x[1].quantity, "temperature_C");
  EXPECT_EQ(x[1].high, 60.0);
  card.fit.erase("data_window");  // a card without a window is not checked
  EXPECT_TRUE(card::outside_data_window(card, c).empty());
}

// A damage model's window keeps the largest damage driver its rows' tests reached, each closed form
// (shear γ → γ/√2; uniaxial ε along the fibre → √(3/2) ε for I, √2 ε for A1, A2; across it the
// point's own lateral strains, PointParts.FritzsonDamageDriversOfATestAreWhatThePointReaches): material 1's
// program (datasets/materials/material-1.csv) — shear 12, 23 to 0.045, uniaxial 22 to 0.015, 33 to
// 0.01 — gives I 0.0318 and A2 0.0318 (shear), A1 0.0141 (uniaxial 33). The complete level holds
// the damage there (docs/decisions.md "Complete level: damage held beyond the tested amplitudes").
TEST(DataWindow, DamageModelsKeepTheLargestDriverTheirTestsReached) {
  data::DynamicTestTable t;
  const std::pair<model::TestMode, const char*> tests[] = {
      {model::TestMode::shear, "12"}, {model::TestMode::shear, "23"}, {model::TestMode::uniaxial, "22"},
      {model::TestMode::uniaxial, "33"}, {model::TestMode::bulk, ""}};
  const double largest[] = {0.045, 0.045, 0.015, 0.01, 0.001};
  for (int k = 0; k < 5; ++k)
    for (double a : {0.005, largest[k]}) {
      data::DynamicTestRow row;
      row.condition.mode = tests[k].first, row.condition.orientation = tests[k].second;
      row.condition.strain_amplitude = a;
      t.rows.push_back(row);
    }
  const card::Card truth = card::load_card(std::string(FITLIB_SOURCE_DIR) + "/datasets/cards/material-1-true.json");
  const auto model = truth.model();
  const std::vector<double> p = truth.values();
  const auto w = card::data_window_json(t, model.get(), p);
  ASSERT_TRUE(w.contains("damage_driver")) << w.dump();
  const std::vector<double> d = w["damage_driver"];
  ASSERT_EQ(d.size(), 3u);
  EXPECT_NEAR(d[0], 0.045 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(d[1], std::sqrt(2.0) * 0.01, 1e-4);  // K/G ~ 10³: the contraction −ε/2 to 10⁻³
  EXPECT_NEAR(d[2], 0.045 / std::sqrt(2.0), 1e-15);
  card::Card card;
  card.model_kind = "fritzson";
  card.model_options = {{"reference_C", 23.0}};
  card.fit["data_window"] = w;
  EXPECT_EQ(card::DataWindow(card).damage_drivers(), d);
  EXPECT_FALSE(card::data_window_json(t, model::make_model("elastic-iso", {}).get(), {}).contains("damage_driver"));
  card::Card held = truth;
  held.fit["data_window"] = w;
  EXPECT_EQ(card::DataWindow(card::card_from_json(card::card_to_json(held))).damage_drivers(), d);
  for (const nlohmann::json bad : {nlohmann::json{0.03, "x", 0.03}, nlohmann::json{0.03, 0.01}, nlohmann::json{0.03, -0.01, 0.03}}) {
    held.fit["data_window"]["damage_driver"] = bad;  // a card read from a file: refused at the key
    try {
      card::card_from_json(card::card_to_json(held), "held.json");
      ADD_FAILURE() << bad;
    } catch (const core::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("fit.data_window.damage_driver"), std::string::npos) << e.what();
    }
  }
}

// With a temperature law the frequency bound is the rows' reduced frequency f·a_T(T): 100 Hz
// measured at 60 °C is data at 100·a_T(60) Hz at the reference, and at temperature T the window
// is [lo, hi] / a_T(T) (closed-form WLF below).
TEST(DataWindow, ReducedFrequencyWithATemperatureLaw) {
  card::Card card;
  card.model_kind = "prony";
  card.model_options = {{"terms", 2}, {"mode", "shear"}, {"temperature_law", "wlf"}, {"reference_C", 23.0}};
  const auto model = card.model();
  ASSERT_EQ(model->parameters().size(), 7u);  // M_inf, M_1, M_2, tau_1, tau_2, C1, C2
  for (double v : {2.0, 3.0, 5.0, 0.1, 10.0, 8.86, 101.6}) {
    card::ParameterEstimate p;
    p.value = v;
    card.parameters.push_back(p);
  }
  const auto log_aT = [](double T) { return -8.86 * (T - 23.0) / (101.6 + T - 23.0); };
  const data::DynamicTestTable t = corners_0p1_100Hz_23_60C();
  card.fit["data_window"] = card::data_window_json(t, model.get(), card.values());
  const auto& reduced = card.fit["data_window"]["reduced_frequency_Hz"];
  EXPECT_NEAR(reduced[0].get<double>(), 0.1 * std::pow(10.0, log_aT(60.0)), 1e-12 * 0.1);
  EXPECT_NEAR(reduced[1].get<double>(), 100.0, 1e-12 * 100.0);
  model::TestCondition c = at(model::TestMode::shear, 1e-3);  // below 0.1 Hz, inside at 23 °C
  c.temperature_C = 23.0;
  EXPECT_TRUE(card::outside_data_window(card, c).empty());
  c.temperature_C = 40.0;  // at 40 °C the same frequency reduces below the window's low end
  const auto x = card::outside_data_window(card, c);
  ASSERT_EQ(x.size(), 1u);
  EXPECT_EQ(x[0].key, "reduced_frequency_Hz");
  EXPECT_NEAR(x[0].low, reduced[0].get<double>() / std::pow(10.0, log_aT(40.0)), 1e-9 * x[0].low);
}

// The low bound holds however many decades lie below the high one (the slack is relative to each
// bound): 1e-6 Hz at the reference is below a reduced window that starts at 6.6e-5 Hz.
TEST(DataWindow, LowBoundHoldsManyDecadesBelowTheHighOne) {
  card::Card card = two_term_card("shear");
  card.fit["data_window"] = {{"frequency_Hz", {1e-5, 1e9}}};
  const auto x = card::outside_data_window(card, at(model::TestMode::shear, 1e-6));
  ASSERT_EQ(x.size(), 1u);
  EXPECT_EQ(x[0].low, 1e-5);
  EXPECT_TRUE(card::outside_data_window(card, at(model::TestMode::shear, 1e-5 * (1 - 1e-12))).empty());
}

