// Hyperelastic fits and cards (docs/hyperelastic.md): synthetic data of known truth recover their
// parameters; Treloar's data (datasets/materials/treloar1944-czhao.csv) are fitted within the
// reference figures of datasets/README.md; Drucker instability within the data is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fitlib/card/hyperelastic.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/data/quasi_static.hpp"
#include "fitlib/fit/hyperelastic.hpp"

using namespace fitlib;
using model::DeformationMode;

namespace {

data::QuasiStaticTable treloar() {
  return data::read_quasi_static_table(std::string(FITLIB_SOURCE_DIR) + "/datasets/materials/treloar1944-czhao.csv");
}

data::QuasiStaticTable only(const data::QuasiStaticTable& t, std::initializer_list<DeformationMode> modes) {
  data::QuasiStaticTable out = t;
  out.rows.clear();
  for (const auto& r : t.rows)
    if (std::find(modes.begin(), modes.end(), r.mode) != modes.end()) out.rows.push_back(r);
  return out;
}

data::QuasiStaticRow row(DeformationMode mode, double x, double stress) {
  data::QuasiStaticRow r;
  r.mode = mode, r.abscissa = x, r.stress_MPa = stress;
  return r;
}

// The law's stresses at Treloar-like stretches in three modes (and volumetric for a compressible law).
data::QuasiStaticTable synthetic(const model::Model& m, const std::vector<double>& p) {
  data::QuasiStaticTable t;
  for (DeformationMode mode : {DeformationMode::uniaxial, DeformationMode::equibiaxial, DeformationMode::planar})
    for (double x : {0.7, 0.85, 1.1, 1.4, 2.0, 3.0, 4.0})
      t.rows.push_back(row(mode, x, m.hyperelastic()->nominal_stress(p.data(), mode, x)));
  if (m.hyperelastic()->compressible())
    for (double J : {0.97, 0.98, 0.99, 0.995})
      t.rows.push_back(row(DeformationMode::volumetric, J, m.hyperelastic()->nominal_stress(p.data(), DeformationMode::volumetric, J)));
  return t;
}

double figure(const fit::HyperelasticFitResult& r, DeformationMode mode) {
  for (const auto& f : r.figures)
    if (f.mode == mode) return f.rms_rel_error;
  return NAN;
}

}  // namespace

TEST(HyperelasticFit, SyntheticDataOfKnownTruthRecoverTheParameters) {
  struct Truth {
    std::string kind;
    nlohmann::json options;
    std::vector<double> p;
  };
  const std::vector<Truth> truths = {
      {"neo-hooke", {}, {0.3}},
      {"mooney-rivlin", {{"terms", 3}}, {0.25, 0.05, 0.002}},
      {"yeoh", {{"compressible", true}}, {0.2, -0.002, 5e-5, 0.004}},
      {"reduced-polynomial", {{"terms", 2}}, {0.2, 0.001}},
      {"ogden", {{"terms", 2}}, {0.4, 1.5, 0.005, 5.0}},
      {"arruda-boyce", {}, {0.33, 5.0}},
      {"gent", {}, {0.34, 90.0}}};
  for (const auto& t : truths) {
    const auto m = model::make_model(t.kind, t.options);
    auto r = fit::fit_hyperelastic(synthetic(*m, t.p), m);
    if (t.kind == "ogden" && r.values[1] > r.values[3])  // Ogden's terms are interchangeable
      std::swap(r.values[0], r.values[2]), std::swap(r.values[1], r.values[3]);
    for (std::size_t k = 0; k < t.p.size(); ++k)
      EXPECT_NEAR(r.values[k], t.p[k], 1e-5 * std::abs(t.p[k]) + 1e-9) << t.kind << " " << m->parameters()[k].name;
    EXPECT_TRUE(r.acceptable()) << t.kind << ": " << (r.warnings.empty() ? "" : r.warnings[0]);
  }
}

TEST(HyperelasticFit, NoisySyntheticOgdenRecoversItsTruthWithinTheStatedUncertainty) {
  const auto m = model::make_model("ogden", {{"terms", 2}});
  const std::vector<double> truth = {0.4, 1.5, 0.005, 5.0};
  auto t = synthetic(*m, truth);
  double sign = 1.0;
  for (auto& r : t.rows) r.stress_MPa *= 1.0 + 0.01 * (sign = -sign);  // ±1 % alternating
  const auto r = fit::fit_hyperelastic(t, m);
  for (std::size_t k = 0; k < truth.size(); ++k) {
    ASSERT_TRUE(r.std_error[k]) << k;
    EXPECT_LT(std::abs(r.values[k] - truth[k]), 4.0 * *r.std_error[k] + 1e-3 * std::abs(truth[k])) << k;
  }
}

TEST(HyperelasticFit, TreloarFitsAreWithinTheReferenceFigures) {
  // Reference rms relative errors (%) of fits to uniaxial + equibiaxial, and the held-out planar
  // figure (datasets/README.md "Treloar (1944)", from the external folder's README).
  struct Ref {
    std::string kind;
    nlohmann::json options;
    double ut, et, ps;
  };
  const std::vector<Ref> refs = {{"neo-hooke", {}, 28.6, 14.2, 17.8},     {"mooney-rivlin", {}, 28.3, 11.3, 16.3},
                                 {"yeoh", {}, 10.7, 15.3, 10.8},          {"ogden", {{"terms", 2}}, 9.1, 14.4, 10.8},
                                 {"ogden", {{"terms", 3}}, 4.9, 8.7, 9.67}, {"arruda-boyce", {}, 14.9, 17.1, 17.5},
                                 {"gent", {}, 15.3, 17.4, 18.1}};
  const auto all = treloar();
  const auto fitted = only(all, {DeformationMode::uniaxial, DeformationMode::equibiaxial});
  const auto planar = only(all, {DeformationMode::planar});
  for (const auto& ref : refs) {
    const auto m = model::make_model(ref.kind, ref.options);
    const auto r = fit::fit_hyperelastic(fitted, m);
    const auto held_out = fit::hyperelastic_figures(*m->hyperelastic(), r.values.data(), planar);
    const double ut = 100 * figure(r, DeformationMode::uniaxial), et = 100 * figure(r, DeformationMode::equibiaxial);
    const double ps = 100 * held_out.at(0).rms_rel_error;
    std::printf("treloar UT+ET %-18s %s: UT %.2f %% (ref %.2f), ET %.2f %% (ref %.2f), held-out PS %.2f %% (ref %.2f)\n",
                ref.kind.c_str(), ref.options.dump().c_str(), ut, ref.ut, et, ref.et, ps, ref.ps);
    // The objective is the reference's (rms relative error, equal weights): the joint rms may not be worse.
    EXPECT_LE(std::hypot(ut, et) / std::sqrt(2.0), std::hypot(ref.ut, ref.et) / std::sqrt(2.0) * 1.005 + 0.05) << ref.kind;
    EXPECT_LE(ps, ref.ps * 1.10 + 0.3) << ref.kind;
    for (const auto& s : r.stability) EXPECT_FALSE(s.inside_data) << ref.kind;
  }
}

TEST(HyperelasticFit, UnstableWithinTheDataIsRefusedAndBeyondItIsAWarning) {
  // Mooney–Rivlin fitted to Treloar's uniaxial rows alone turns C01 negative and Drucker-unstable
  // (reference: "no / no"): within the uniaxial data it is refused, naming mode and stretch.
  const auto all = treloar();
  const auto m = model::make_model("mooney-rivlin", {});
  try {
    fit::fit_hyperelastic(only(all, {DeformationMode::uniaxial}), m);
    ADD_FAILURE() << "an unstable fit within the data was accepted";
  } catch (const core::NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("uniaxial tension from stretch"), std::string::npos) << e.what();
  }
  // Uniaxial rows of that unstable set itself up to stretch 1.5: the fit recovers it, and the
  // instability (from 1.85 in uniaxial tension) lies beyond the data: a warning names it.
  const std::vector<double> unstable = {0.2158, -0.06304};
  data::QuasiStaticTable low;
  for (double x : {1.1, 1.2, 1.3, 1.4, 1.5})
    low.rows.push_back(row(DeformationMode::uniaxial, x, m->hyperelastic()->nominal_stress(unstable.data(), DeformationMode::uniaxial, x)));
  const auto r = fit::fit_hyperelastic(low, m);
  std::string all_warnings;
  for (const auto& w : r.warnings) all_warnings += w + "\n";
  EXPECT_LT(r.values[1], 0.0);
  EXPECT_NE(all_warnings.find("Drucker-unstable in uniaxial tension from stretch"), std::string::npos) << all_warnings;
  EXPECT_NE(all_warnings.find("beyond the data"), std::string::npos) << all_warnings;
}

TEST(HyperelasticFit, GentsLockingIsANoteNotAnInstability) {
  const auto m = model::make_model("gent", {});
  const auto r = fit::fit_hyperelastic(synthetic(*m, {0.34, 90.0}), m);
  bool locking = false;
  for (const auto& s : r.stability) locking = locking || (s.locking && s.mode == DeformationMode::uniaxial && s.tension);
  EXPECT_TRUE(locking);
  EXPECT_TRUE(r.acceptable()) << r.warnings.front();
}

TEST(HyperelasticFit, CardRecordsTheFitAndRoundTrips) {
  card::HyperelasticCardOptions o;
  o.model = "ogden";
  o.model_options = {{"terms", 3}};
  o.name = "treloar-ogden3";
  const auto r = card::fit_hyperelastic_card(treloar(), o);
  const card::Card back = card::card_from_json(card::card_to_json(r.card));
  EXPECT_EQ(back.values(), r.card.values());
  EXPECT_EQ(back.model()->hyperelastic()->initial_shear_modulus(back.values().data()),
            r.result.model->hyperelastic()->initial_shear_modulus(r.result.values.data()));
  EXPECT_EQ(r.card.fit["stability"].size(), 6u);
  EXPECT_EQ(r.card.fit["quality"]["figures"].size(), 3u);
  // Same input and seed: the same bytes.
  EXPECT_EQ(card::card_to_json(card::fit_hyperelastic_card(treloar(), o).card).dump(),
            card::card_to_json(r.card).dump());
}
