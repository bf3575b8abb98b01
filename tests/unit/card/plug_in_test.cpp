// How a new model plugs in (docs/model.md): a standard linear solid defined only in this test
// and one register_model line is fitted, written as a card, read back and evaluated, exported to
// FE decks and driven as a material point — with no change to fit, card or scene.
#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include <cmath>
#include <complex>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "fitlib/card/card.hpp"
#include "fitlib/card/export.hpp"
#include "fitlib/card/from_fit.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/model.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib {
namespace {

// G*(ω) = G_e + G_m iωτ/(1 + iωτ) in shear, elastic bulk modulus K.
class StandardLinearSolid final : public model::Model {
 public:
  std::string kind() const override { return "standard-linear-solid"; }
  const std::vector<core::ParameterSpec>& parameters() const override {
    static const std::vector<core::ParameterSpec> specs = {
        {"G_e", "MPa", 0.0, 1e6, core::Transform::log, "elastic", 1.0, true},
        {"G_m", "MPa", 0.0, 1e6, core::Transform::log, "viscous", 1.0, true},
        {"tau_m", "s", 1e-9, 1e9, core::Transform::log, "time", 1.0, false},
        {"K", "MPa", 0.0, 1e7, core::Transform::log, "volumetric", 2000.0, false}};
    return specs;
  }
  nlohmann::json options() const override { return nlohmann::json::object(); }
  model::TestMode native_mode() const override { return model::TestMode::shear; }

  model::Moduli<double> moduli(const double* p, const model::TestCondition& c) const override {
    Eigen::MatrixXd unused(3, 4);
    return moduli(p, c, unused);
  }
  model::Moduli<double> moduli(const double* p, const model::TestCondition& c,
                               Eigen::Ref<Eigen::MatrixXd> jacobian) const override {
    if (c.mode != model::TestMode::shear) throw core::UsageError("standard-linear-solid: shear tests only");
    const double x = core::angular_frequency(c.frequency_Hz) * p[2], d = 1.0 + x * x;
    jacobian.setZero();
    jacobian(0, 0) = 1.0;
    jacobian(0, 1) = x * x / d;
    jacobian(0, 2) = p[1] * 2.0 * x / (d * d) * x / p[2];  // d/dτ of x²/(1+x²) = 2x/(1+x²)² · x/τ
    jacobian(1, 1) = x / d;
    jacobian(1, 2) = p[1] * (1.0 - x * x) / (d * d) * x / p[2];
    jacobian(2, 0) = 1.0;
    return {p[0] + p[1] * x * x / d, p[1] * x / d, p[0]};
  }
  std::vector<double> stress_response(const double* p, const model::TestCondition&,
                                      const model::StrainHistory& history) const override {
    return series(p).stress(history);
  }
  double relaxation_modulus(const double* p, const model::TestCondition&, double t_s) const override {
    return series(p).relaxation(t_s);
  }
  double creep_compliance(const double* p, const model::TestCondition&, double t_s) const override {
    const double glassy = p[0] + p[1], retardation_s = p[2] * glassy / p[0];
    return 1.0 / p[0] - (1.0 / p[0] - 1.0 / glassy) * std::exp(-t_s / retardation_s);
  }
  bool maxwell_series(const double* p, model::MaxwellSeries* out) const override {
    *out = series(p);
    return true;
  }
  double bulk_modulus(const double* p) const override { return p[3]; }
  std::shared_ptr<const model::MaterialPoint> material_point(const double* p,
                                                             const model::PointOptions& options) const override {
    return model::series_point(std::make_shared<StandardLinearSolid>(*this), std::vector<double>(p, p + 4), options);
  }

 private:
  static model::MaxwellSeries series(const double* p) { return {p[0], {p[1]}, {p[2]}}; }
};

// The one registry line (once per process).
void register_standard_linear_solid() {
  static const bool done = [] {
    model::register_model("standard-linear-solid",
                          [](const nlohmann::json&) { return std::make_shared<StandardLinearSolid>(); });
    return true;
  }();
  (void)done;
}

constexpr double kGe = 1.5, kGm = 6.0, kTau = 0.02, kK = 2000.0;

data::DynamicTestTable exact_table() {
  const StandardLinearSolid truth;
  const double p[4] = {kGe, kGm, kTau, kK};
  data::DynamicTestTable table;
  for (int k = 0; k < 21; ++k) {
    data::DynamicTestRow row;
    row.condition.mode = model::TestMode::shear;
    row.condition.frequency_Hz = std::pow(10.0, -1.0 + 0.2 * k);
    const auto m = truth.moduli(p, row.condition);
    row.storage_MPa = m.storage;
    row.loss_MPa = m.loss;
    row.source_file = "synthetic";
    row.source_line = k + 1;
    table.rows.push_back(row);
  }
  table.source_files = {"synthetic"};
  table.source_sha256 = {"0"};
  return table;
}

class PlugIn : public ::testing::Test {
 protected:
  void SetUp() override {
    register_standard_linear_solid();
    fit::FitOptions o;
    o.fixed = {"K"};  // shear data do not inform K
    result_ = fit::fit(model::make_model("standard-linear-solid", {}), table_, o);
    const auto written = card::card_from_fit(result_, o, table_, {"sls", "plug-in test", false});
    const std::string path = fitlib_test::temp_path("sls.json");
    card::save_card(path, written);
    card_ = card::load_card(path);
  }
  data::DynamicTestTable table_ = exact_table();
  fit::FitResult result_;
  card::Card card_;
};

TEST_F(PlugIn, TheRegistryKnowsTheModel) {
  const auto kinds = model::model_kinds();
  EXPECT_NE(std::find(kinds.begin(), kinds.end(), "standard-linear-solid"), kinds.end());
  EXPECT_THROW(model::register_model("prony", [](const nlohmann::json&) { return model::ModelPtr(); }),
               core::UsageError);
}

TEST_F(PlugIn, FitRecoversTheTruthFromExactData) {
  ASSERT_EQ(result_.values.size(), 4u);
  EXPECT_NEAR(result_.values[0], kGe, 1e-6 * kGe);
  EXPECT_NEAR(result_.values[1], kGm, 1e-6 * kGm);
  EXPECT_NEAR(result_.values[2], kTau, 1e-6 * kTau);
  EXPECT_EQ(result_.values[3], kK);
}

TEST_F(PlugIn, TheCardReadsBackAndEvaluatesAsTheFit) {
  EXPECT_EQ(card_.model_kind, "standard-linear-solid");
  const auto m = card_.model();
  const auto values = card_.values();
  for (double f : {0.01, 1.0, 7.9, 1e3}) {
    model::TestCondition c;
    c.frequency_Hz = f;
    const auto a = result_.model->moduli(result_.values.data(), c), b = m->moduli(values.data(), c);
    EXPECT_EQ(a.storage, b.storage) << f;
    EXPECT_EQ(a.loss, b.loss) << f;
  }
}

TEST_F(PlugIn, ExportsWriteThePronyWeightOfTheSolid) {
  const auto values = card_.values();
  const double g1 = values[1] / (values[0] + values[1]);
  card::ExportOptions options;
  options.density_t_per_mm3 = 1.2e-9;  // LS-DYNA's RO
  for (const char* format : {"abaqus", "ansys", "lsdyna"}) {
    std::string deck;
    ASSERT_NO_THROW(deck = card::export_card(card_, format, options)) << format;
    EXPECT_NE(deck.find("standard-linear-solid"), std::string::npos) << format;
  }
  EXPECT_THROW(card::export_card(card_, "calculix"), core::UsageError);  // as for every Prony card
  // Abaqus *VISCOELASTIC, TIME=PRONY: g_1, k_1 (0: a shear card's bulk is elastic), τ_1.
  const std::string abaqus = card::export_card(card_, "abaqus");
  const auto at = abaqus.find("*VISCOELASTIC");
  ASSERT_NE(at, std::string::npos);
  const std::string row = abaqus.substr(abaqus.find('\n', at) + 1);
  EXPECT_NEAR(std::stod(row), g1, 1e-9);
}

TEST_F(PlugIn, TheMaterialPointRelaxesAsTheModel) {
  const auto point = model::make_material_point(*card_.model(), card_.values());
  std::vector<double> state = point->initial_state(), next(point->state_size());
  model::Vector6 strain = model::Vector6::Zero();
  strain[5] = 0.01;  // γ12 step over 1 ns, then held
  point->update(state.data(), strain, 1e-9, NAN, next.data());
  state.swap(next);
  const auto values = card_.values();
  for (int n = 1; n <= 10; ++n) {
    const model::Vector6 sigma = point->update(state.data(), strain, 0.01, NAN, next.data());
    state.swap(next);
    const double t = 1e-9 + 0.01 * n;
    const double expected = card_.model()->relaxation_modulus(values.data(), {}, t) * strain[5];
    EXPECT_NEAR(sigma[5], expected, 1e-7 * std::abs(expected)) << t;
  }
}

TEST_F(PlugIn, TheElasticFidelityIsTheStorageModulus) {
  model::PointOptions options;
  options.fidelity = core::Fidelity::elastic;
  options.frequency_Hz = 3.0;
  const auto point = model::make_material_point(*card_.model(), card_.values(), options);
  model::TestCondition c;
  c.frequency_Hz = 3.0;
  const double storage = card_.model()->moduli(card_.values().data(), c).storage;
  model::Vector6 strain = model::Vector6::Zero();
  strain[5] = 0.002;
  std::vector<double> state = point->initial_state(), next(point->state_size());
  EXPECT_NEAR(point->update(state.data(), strain, 1.0, NAN, next.data())[5], storage * 0.002, 1e-9 * storage);
}

}  // namespace
}  // namespace fitlib
