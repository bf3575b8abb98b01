// Acceptance on pyvisco's master curve against the ANSYS reference terms, and a master curve
// built from raw isotherms (WLF shifts fitted with the Prony series).
#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include <algorithm>
#include <cstdio>

#include "fit_testing.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/parameter.hpp"
#include "fitlib/data/eplexor.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/terms.hpp"

using namespace fitlib;
using namespace fitlib::fit::testing;

namespace {

struct LogRms {
  double storage = 0.0, loss = 0.0;
};

// Independent evaluation of the ANSYS terms on the data points.
LogRms ansys_reference(const data::DynamicTestTable& table) {
  const auto terms = read_ansys_prony(repo_path("datasets/materials/pyvisco-ansys-prony-terms.MPL"));
  EXPECT_EQ(terms.size(), 27u);
  const data::DynamicTestRow* highest = &table.rows.front();
  for (const auto& row : table.rows)
    if (row.condition.frequency_Hz > highest->condition.frequency_Hz) highest = &row;
  const double e0 = highest->storage_MPa;
  LogRms rms;
  for (const auto& row : table.rows) {
    const auto e = normalised_prony(e0, terms, core::angular_frequency(row.condition.frequency_Hz));
    rms.storage += std::pow(std::log10(e.real() / row.storage_MPa), 2);
    rms.loss += std::pow(std::log10(e.imag() / row.loss_MPa), 2);
  }
  rms.storage = std::sqrt(rms.storage / table.rows.size());
  rms.loss = std::sqrt(rms.loss / table.rows.size());
  return rms;
}

}  // namespace

TEST(Pyvisco, AnsysReferenceTermsReproduceThePublishedFigures) {
  const auto table = read_pyvisco("datasets/materials/pyvisco-freq-master.csv");
  ASSERT_EQ(table.rows.size(), 206u);
  const LogRms ansys = ansys_reference(table);
  EXPECT_NEAR(ansys.storage, 0.0107, 0.0005);  // anchors.md
  EXPECT_NEAR(ansys.loss, 0.381, 0.005);
}

// --terms auto with the storage weight that puts the fit past ANSYS on both axes of the
// E′/E″ frontier (the data are not Kramers–Kronig consistent: no fit is best in both).
TEST(Pyvisco, TermsAutoDominatesTheAnsysTermsWithStorageWeight) {
  const auto table = read_pyvisco("datasets/materials/pyvisco-freq-master.csv");
  const LogRms ansys = ansys_reference(table);
  fit::FitOptions o;
  o.storage_weight = 500.0;
  fit::TermOptions t;
  const auto sel = fit::select_terms("prony", {{"mode", "uniaxial"}}, table, o, t);
  std::printf("%s", fit::format_term_table(sel).c_str());
  const auto& m = sel.result.metrics;
  std::printf("chosen %d terms: rms log10 E' %.4f E'' %.4f (ANSYS %.4f %.4f)\n", sel.chosen,
              m.rms_log10_storage, m.rms_log10_loss, ansys.storage, ansys.loss);
  EXPECT_LE(m.rms_log10_storage, ansys.storage);
  EXPECT_LE(m.rms_log10_loss, ansys.loss);
  for (double v : sel.result.values) EXPECT_GE(v, 0.0);
}

// A retardation spectrum is the same function family as a Prony series: with 5 terms it fits the
// master curve as a 5-term Prony card does, and its instantaneous modulus 1/J_g stays under the
// modulus ceiling (unbounded, J_g went to 1e-50: a 9e49 MPa instantaneous modulus in the card).
TEST(Pyvisco, RetardationSpectrumKeepsItsInstantaneousModulusUnderTheCeiling) {
  const auto table = read_pyvisco("datasets/materials/pyvisco-freq-master.csv");
  double storage_max = 0.0;
  for (const auto& row : table.rows) storage_max = std::max(storage_max, row.storage_MPa);
  const fit::FitOptions o;
  const auto ret = fit::fit(model::make_model("retardation", {{"mode", "uniaxial"}, {"terms", 5}}), table, o);
  const auto prony = fit::fit(model::make_model("prony", {{"mode", "uniaxial"}, {"terms", 5}}), table, o);
  EXPECT_DOUBLE_EQ(ret.admissible.glassy_modulus_max_MPa, o.modulus_ceiling * storage_max);
  EXPECT_GE(ret.values[0], (1.0 - 1e-12) / ret.admissible.glassy_modulus_max_MPa);  // J_g
  EXPECT_NEAR(ret.metrics.rms_log10_storage / prony.metrics.rms_log10_storage, 1.0, 0.1);
  EXPECT_NEAR(ret.metrics.rms_log10_loss / prony.metrics.rms_log10_loss, 1.0, 0.1);
}

// Raw isotherms (21 temperatures, T_ref = −5 °C as in pyvisco's shift table): WLF shifts and
// the Prony series fitted together by a staged schedule — moduli by NNLS on a broad τ grid,
// then moduli and shifts with τ held, then everything.
TEST(Pyvisco, MasterCurveFromRawIsothermsWithWlf) {
  const auto table = read_pyvisco("datasets/materials/pyvisco-freq-raw.csv");
  ASSERT_EQ(table.rows.size(), 210u);
  const int n = 16;
  const auto model = model::make_model("prony", {{"terms", n}, {"mode", "uniaxial"},
                                                 {"temperature_law", "wlf"}, {"reference_C", -5.0}});
  const auto& specs = model->parameters();
  const int c1 = core::find_parameter(specs, "C1"), c2 = core::find_parameter(specs, "C2");
  auto start = model->initial_parameters(fit::summarize(table));
  for (int i = 0; i < n; ++i) start[1 + n + i] = std::pow(10.0, -14.0 + 26.0 * i / (n - 1));
  start[c1] = 17.44;  // the "universal" WLF constants as a start
  start[c2] = 51.6;
  const std::string schedule = fitlib_test::temp_path("fit_master_schedule.json");
  core::write_file_atomically(schedule, R"({"stages": [
    {"name": "moduli", "free": ["*"], "backend": "nnls"},
    {"name": "shifts", "free": ["group:elastic", "group:viscous", "group:shift"], "backend": "ceres"},
    {"name": "all", "free": ["*"], "backend": "ceres"}]})");
  fit::FitOptions o;
  o.backend = fit::Backend::staged;
  o.schedule_path = schedule;
  const auto r = fit::fit(model, table, o, &start);
  std::printf("raw isotherms: rms log10 E' %.4f E'' %.4f, C1 %.2f C2 %.1f, %.0f ms\n",
              r.metrics.rms_log10_storage, r.metrics.rms_log10_loss, r.values[c1], r.values[c2],
              1e3 * r.metrics.wall_time_s);
  // pyvisco, with free per-isotherm shifts: (0.0047, 0.188). One WLF law cannot follow its
  // shifts at the glassy (cold) end, so E′ is worse and E″ better here.
  EXPECT_LT(r.metrics.rms_log10_storage, 0.07);
  EXPECT_LT(r.metrics.rms_log10_loss, 0.15);
  EXPECT_GT(r.values[c2], 46.0);  // T_ref − T_min = 45 °C: the pole stays below the data
  // Shifts against pyvisco's (fitted per isotherm, not WLF): within 3 decades from −35 °C up;
  // at −50 °C (glassy plateau, shifts barely determined by the data) only the sign.
  const std::vector<std::pair<double, double>> pyvisco = {
      {100, -11.7}, {70, -8.46}, {40, -5.64}, {10, -2.4}, {-5, 0}, {-20, 2.58}, {-35, 6.3}};
  auto log_shift = [&](double t) { return -r.values[c1] * (t + 5.0) / (r.values[c2] + t + 5.0); };
  for (const auto& [t, log_at] : pyvisco) EXPECT_NEAR(log_shift(t), log_at, 3.0) << "T = " << t;
  EXPECT_GT(log_shift(-50.0), log_shift(-35.0));
}

// A fractional Zener on pyvisco's EPLEXOR shear master curve (183 rows over 33 decades): the local
// descent from the model's start stopped with alpha at its lower bound, 500 % mean storage error;
// the automatic backend's multistart check keeps the lower cost (the nlopt backend's optimum), and
// the verdict still says the four-parameter law misses these data.
TEST(Pyvisco, SmallModelsGetTheMultistartCheck) {
  const auto table = data::read_eplexor(repo_path("datasets/materials/pyvisco-eplexor-master-shear.xls")).table;
  const auto model = model::make_model("fractional-zener", {{"mode", "shear"}});
  const auto automatic = fit::fit(model, table, fit::FitOptions{});
  fit::FitOptions global;
  global.backend = fit::Backend::nlopt;
  const auto nlopt = fit::fit(model, table, global);
  EXPECT_LE(automatic.metrics.cost, nlopt.metrics.cost * (1 + 1e-6));
  EXPECT_LT(automatic.metrics.cost, 30.0);  // the local descent alone: 128.3
  EXPECT_NE(automatic.backend_used.find("nlopt"), std::string::npos) << automatic.backend_used;
  EXPECT_FALSE(automatic.quality.acceptable());
  // A Prony series of several terms is not checked (its NNLS start is the global one).
  const auto prony = fit::fit(model::make_model("prony", {{"mode", "shear"}, {"terms", 4}}), table, fit::FitOptions{});
  EXPECT_EQ(prony.backend_used.find("nlopt"), std::string::npos) << prony.backend_used;
}
