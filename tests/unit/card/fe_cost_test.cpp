// What a card costs an FE model (issue 35 item 3, card "fit.fe_cost" and the fit summary): its
// active series terms and the state variables they add at every integration point — 6 (one
// symmetric stress tensor) per term, 12 when the bulk relaxes too (a uniaxial card without K).
#include <gtest/gtest.h>

#include <string>

#include "fitlib/card/card.hpp"
#include "fitlib/card/fit_card.hpp"
#include "fitlib/card/from_fit.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib {
namespace {

std::string source(const std::string& path) { return std::string(FITLIB_SOURCE_DIR) + "/" + path; }

// The bundled 6-term shear truth (datasets/README.md): six positive G_i, the bulk elastic.
TEST(FeCost, ShearCardCountsSixStateVariablesPerPositiveTerm) {
  const card::Card c = card::load_card(source("datasets/cards/synthetic-prony-shear-true.json"));
  std::vector<double> values = c.values();
  const auto model = c.model();
  const card::FeCost cost = card::fe_cost(*model, values);
  EXPECT_EQ(cost.terms, 6);
  EXPECT_EQ(cost.state_variables, 36);
  // A zero term adds no state variable (the solver drops it).
  const auto& params = model->parameters();
  for (std::size_t i = 0; i < params.size(); ++i)
    if (params[i].name == "G_3") values[i] = 0.0;
  const card::FeCost fewer = card::fe_cost(*model, values);
  EXPECT_EQ(fewer.terms, 5);
  EXPECT_EQ(fewer.state_variables, 30);
}

// pyvisco's tensile master: a uniaxial card without K, so the bulk relaxes with the same weights
// (6 deviatoric + 6 volumetric numbers per term); the card states what fe_cost computes.
TEST(FeCost, UniaxialCardWithoutBulkModulusCountsTwelvePerTermAndTheCardSaysSo) {
  data::ReadOptions read;
  read.format = data::TableFormat::pyvisco;
  read.has_default_mode = true;
  read.default_mode = model::TestMode::uniaxial;
  const auto table = data::read_dynamic_table(source("datasets/materials/pyvisco-freq-master.csv"), read);
  card::FitCardOptions o;
  o.model = "prony";
  o.terms = "auto";
  o.model_options = {{"mode", "uniaxial"}, {"reference_C", -5.0}};
  const card::FitCardResult r = card::fit_card(table, o);
  const auto values = r.card.values();
  model::MaxwellSeries s;
  ASSERT_TRUE(r.card.model()->maxwell_series(values.data(), &s));
  int positive = 0;
  for (double m : s.moduli) positive += m > 0.0;
  ASSERT_TRUE(r.card.fit.contains("fe_cost"));
  EXPECT_EQ(r.card.fit["fe_cost"]["terms"].get<int>(), positive);
  EXPECT_EQ(r.card.fit["fe_cost"]["state_variables_per_integration_point"].get<int>(), 12 * positive);
}

}  // namespace
}  // namespace fitlib
