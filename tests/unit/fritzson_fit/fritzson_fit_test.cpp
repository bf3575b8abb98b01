// Fitting Fritzson's model as in Report II §6 (constitutive-model.md §6): relative errors of the
// mean, dynamic and loss moduli, the shipped staged schedules (datasets/schedules), default
// starts, and the identifiability report. Ground truth: the synthetic materials 1 and 2
// (datasets/materials, 1.5 % seeded scatter) and their true cards (datasets/cards).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fitlib/card/card.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/problem.hpp"
#include "fitlib/fit/staged.hpp"
#include "fitlib/model/model.hpp"

using namespace fitlib;

namespace {

const std::string kRoot = FITLIB_SOURCE_DIR;

struct Material {
  data::DynamicTestTable table;
  std::vector<double> truth;
  model::ModelPtr model;
};

Material load(const std::string& name, const std::string& kind) {
  return {data::read_dynamic_table(kRoot + "/datasets/materials/" + name + ".csv"),
          card::load_card(kRoot + "/datasets/cards/" + name + "-true.json").values(),
          model::make_model(kind, nullptr)};
}

fit::FitResult staged_fit(const Material& m, const std::string& schedule,
                          fit::ResidualKind residual = fit::ResidualKind::relative) {
  fit::FitOptions options;
  options.backend = fit::Backend::staged;
  options.residual = residual;
  options.schedule_path = kRoot + "/datasets/schedules/" + schedule;
  return fit::fit(m.model, m.table, options);
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Counts the parameters with an interval and those whose interval holds the true value; every
// parameter without an interval must say why, and one called not identifiable must be named
// by the identifiability report.
struct Coverage {
  int with_interval = 0, covered = 0;
};

Coverage check_intervals(const fit::FitResult& r, const std::vector<double>& truth) {
  Coverage c;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const auto& pr = r.parameters[i];
    if (!pr.ci95_low) {
      EXPECT_FALSE(pr.reason.empty()) << pr.name;
      if (pr.reason.rfind("not identifiable", 0) == 0) {
        EXPECT_TRUE(contains(r.identifiability.not_identifiable, pr.name)) << pr.name;
      }
      continue;
    }
    ++c.with_interval;
    const bool inside = *pr.ci95_low <= truth[i] && truth[i] <= *pr.ci95_high;
    c.covered += inside;
    EXPECT_TRUE(inside) << pr.name << " true " << truth[i] << " fitted " << pr.value << " ["
                        << *pr.ci95_low << ", " << *pr.ci95_high << "]";
  }
  return c;
}

}  // namespace

// Acceptance (issue 3, item 5): material 1, all 38 parameters, default start, shipped schedule.
// Observed: mean relative error 1.19 % (the 1.5 % scatter alone gives ≈ 1.2 %), 29 parameters
// with an interval, all 29 cover the true value.
TEST(FritzsonFit, Material1StagedFromDefaultStartRecoversDataAndParameters) {
  const Material m = load("material-1", "fritzson");
  const fit::FitResult r = staged_fit(m, "fritzson.json");
  EXPECT_LE(r.metrics.mean_rel_error, 0.02);
  const Coverage c = check_intervals(r, m.truth);
  std::printf("material 1: mean relative error %.2f %%, %d of %d intervals cover the truth\n",
              100 * r.metrics.mean_rel_error, c.covered, c.with_interval);
  EXPECT_GE(c.with_interval, 25);

  // The A2 (fibre shear) damage constants are seen only through the 13/23 shear tests, at three
  // amplitudes (two at 100 °C) that also drive the isotropic damage: three levels cannot fix a
  // scale and h1's three constants, and μ_A2 (shared with h2) drags the viscous A2 constants
  // along: the report must name all of them. C_d (damage evolution) has no effect on the
  // saturated complex form at all.
  const auto& named = r.identifiability.not_identifiable;
  for (const char* name : {"beta1_A2", "alpha1_A2", "mu_A2", "beta2_A2", "alpha2_A2", "C44_Am",
                           "C44_Ad", "C44_Av", "C_d"})
    EXPECT_TRUE(contains(named, name)) << name;
  EXPECT_FALSE(r.identifiability.null_space.empty());
  // Everything of the isotropic part, K and the A1 part except what the report names is pinned.
  for (const char* name : {"K", "G_Im", "G_Id", "G_Iv", "tau_I", "mu_I", "c1_I", "C33_Av", "c1_A1"})
    EXPECT_FALSE(contains(named, name)) << name;
}

// Material 2 (isotropic, 14 parameters): only C_d is not identifiable.
TEST(FritzsonFit, Material2StagedFromDefaultStartRecoversDataAndParameters) {
  const Material m = load("material-2", "fritzson-iso");
  const fit::FitResult r = staged_fit(m, "fritzson-iso.json");
  EXPECT_LE(r.metrics.mean_rel_error, 0.02);
  const Coverage c = check_intervals(r, m.truth);
  std::printf("material 2: mean relative error %.2f %%, %d of %d intervals cover the truth\n",
              100 * r.metrics.mean_rel_error, c.covered, c.with_interval);
  EXPECT_EQ(c.with_interval, 13);
  EXPECT_EQ(r.identifiability.not_identifiable, std::vector<std::string>{"C_d"});
}

// The log10 objective (the CLI's default) with the same schedules also reaches the data.
TEST(FritzsonFit, LogResidualsWithTheSameSchedulesReachTheData) {
  EXPECT_LE(staged_fit(load("material-1", "fritzson"), "fritzson.json", fit::ResidualKind::log10)
                .metrics.mean_rel_error,
            0.02);
  EXPECT_LE(staged_fit(load("material-2", "fritzson-iso"), "fritzson-iso.json",
                       fit::ResidualKind::log10)
                .metrics.mean_rel_error,
            0.02);
}

// The shipped schedules parse and every selector matches a parameter of their model.
TEST(FritzsonFit, ShippedSchedulesSelectExistingParameters) {
  for (const auto& [file, kind] : {std::pair<const char*, const char*>{"fritzson.json", "fritzson"},
                                   {"fritzson-iso.json", "fritzson-iso"}}) {
    const fit::Schedule s = fit::load_schedule(kRoot + "/datasets/schedules/" + file);
    ASSERT_FALSE(s.stages.empty());
    const auto model = model::make_model(kind, nullptr);
    for (const auto& stage : s.stages) {
      EXPECT_FALSE(fit::select_parameters(model->parameters(), stage.free, "free").empty());
      if (!stage.lock.empty()) fit::select_parameters(model->parameters(), stage.lock, "lock");
    }
    EXPECT_EQ(s.stages.back().backend, "ceres") << file << ": a Ceres finish";
  }
}

// The Problem's Jacobian (one model evaluation per distinct test condition, the model's
// per-orientation jet passes and the implicit derivative of the uniaxial damage drivers)
// against central differences of its own residuals, material 1 at its default start.
TEST(FritzsonFit, ProblemJacobianMatchesCentralDifferences) {
  const Material m = load("material-1", "fritzson");
  fit::FitOptions options;
  options.residual = fit::ResidualKind::relative;
  const auto start = m.model->initial_parameters(fit::summarize(m.table));
  fit::Problem problem(m.model, m.table, options, start);
  const int rows = problem.num_residuals(), nf = problem.num_free();
  std::vector<double> r0(rows), jac(static_cast<std::size_t>(rows) * nf), up(rows), down(rows);
  ASSERT_TRUE(problem.evaluate(problem.natural(), r0.data(), jac.data()));
  const Eigen::VectorXd x0 = problem.to_x(problem.natural());
  double worst = 0.0;
  for (int k = 0; k < nf; ++k) {
    const double h = 1e-6 * std::max(1.0, std::abs(x0[k]));
    std::vector<double> p = problem.natural();
    Eigen::VectorXd x = x0;
    x[k] = x0[k] + h;
    problem.from_x(x.data(), p);
    ASSERT_TRUE(problem.evaluate(p, up.data(), nullptr));
    x[k] = x0[k] - h;
    problem.from_x(x.data(), p);
    ASSERT_TRUE(problem.evaluate(p, down.data(), nullptr));
    // Error relative to the column's largest entry (columns of parameters a row does not
    // depend on are exactly zero in both).
    double error = 0.0, scale = 1e-300;
    for (int e = 0; e < rows; ++e) {
      const double numeric = (up[e] - down[e]) / (2 * h);
      const double analytic = jac[static_cast<std::size_t>(e) * nf + k];
      error = std::max(error, std::abs(numeric - analytic));
      scale = std::max(scale, std::abs(numeric));
    }
    if (scale > 1e-12) worst = std::max(worst, error / scale);
  }
  std::printf("worst relative Jacobian error %.2e over %d x %d\n", worst, rows, nf);
  EXPECT_LT(worst, 1e-5);
}

// Repeat specimens (same test condition) share one evaluation: their residuals differ only by
// their data. Material 1 has 160 rows at fewer distinct conditions.
TEST(FritzsonFit, RepeatedConditionsGiveTheModelValueOfTheirCondition) {
  const Material m = load("material-1", "fritzson");
  fit::FitOptions options;
  options.residual = fit::ResidualKind::relative;
  fit::Problem problem(m.model, m.table, options, m.truth);
  std::vector<double> r(problem.num_residuals());
  ASSERT_TRUE(problem.evaluate(problem.natural(), r.data(), nullptr));
  for (int e = 0; e < problem.num_residuals(); ++e) {
    const auto& en = problem.entries()[e];
    const auto mod = m.model->moduli(m.truth.data(), m.table.rows[en.row].condition);
    const double value = en.component == 0 ? mod.storage : en.component == 1 ? mod.loss : mod.mean;
    EXPECT_NEAR(r[e], en.sqrt_weight * (value - en.data) / en.scale, 1e-12) << "row " << en.row;
  }
}
