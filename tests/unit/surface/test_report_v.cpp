// Report V §5.3 worked example and the parameter counts of its figure captions (spec §3.3, §3.4).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "designs.hpp"
#include "fitlib/core/error.hpp"

using namespace fitlib::surface;
using namespace fitlib::surface::testing;

namespace {

// Independent evaluation straight from Eqs 5.2, 5.21-5.24 (amplitude linear, frequency log10,
// temperature linear), for ground truth.
double equation_5_24(const double rc[3][3][3], double amplitude, double f_Hz, double T_C) {
  const double u = (amplitude - 0.005) / (0.045 - 0.005);
  const double v = (std::log10(f_Hz) - std::log10(3.0)) / (std::log10(60.0) - std::log10(3.0));
  const double w = (T_C - 23.0) / (100.0 - 23.0);
  auto B = [](int i, double t) { return i == 0 ? (1 - t) * (1 - t) : i == 1 ? 2 * t * (1 - t) : t * t; };
  double sum = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int l = 0; l < 3; ++l) sum += rc[i][j][l] * B(i, u) * B(j, v) * B(l, w);
  return sum;
}

// 47 points: two samples in every occupied cell but the first (Fig 6.5/6.6).
int shear_replicates(std::size_t cell) { return cell == 0 ? 1 : 2; }

}  // namespace

TEST(ReportV, WorkedExample27To24DegreesOfFreedom) {
  // Ground truth: control points obeying Eqs 5.30-5.32.
  double rc[3][3][3];
  fitlib::core::Rng rng(11);
  for (auto& a : rc)
    for (auto& b : a)
      for (double& c : b) c = rng.uniform(2.0, 12.0);
  for (int j = 0; j < 3; ++j) rc[2][j][2] = -rc[0][j][2] + 2 * rc[1][j][2];

  const auto data = make_design(levels(3, 3, 3), shear_has_data, shear_replicates, 0.0, 1,
                                 [&](const double* x) { return equation_5_24(rc, x[0], x[1], x[2]); });
  const Surface s = fit_surface(data, rubber_options());

  EXPECT_EQ(s.statistics.n_points, 47u);
  EXPECT_EQ(s.size(), 27u);
  EXPECT_EQ(s.statistics.n_parameters, 24u);
  EXPECT_EQ(s.statistics.residual_dof, 23u);
  EXPECT_EQ(s.missing_cells.size(), 3u);
  for (const auto& cell : s.missing_cells) {
    EXPECT_EQ(cell[0], 2);
    EXPECT_EQ(cell[2], 2);
  }
  // One group: d²/du² = 0 along amplitude on the temperature face w = 1, three equations, each
  // rc_{0j2} - 2 rc_{1j2} + rc_{2j2} = 0 (Eq 5.29 with B'' = [2, -4, 2], divided by 2).
  ASSERT_EQ(s.constraints.size(), 1u);
  const ConstraintGroup& g = s.constraints[0];
  EXPECT_EQ(g.origin, "missing-cells");
  EXPECT_NE(g.description.find("'strain_amplitude'"), std::string::npos) << g.description;
  EXPECT_NE(g.description.find("'temperature_C' u = 1"), std::string::npos) << g.description;
  ASSERT_EQ(g.equations.size(), 3u);
  for (int j = 0; j < 3; ++j) {
    std::map<std::size_t, double> terms(g.equations[j].terms.begin(), g.equations[j].terms.end());
    ASSERT_EQ(terms.size(), 3u);
    EXPECT_EQ(terms.at(s.flat_index({0, j, 2})), 1.0);
    EXPECT_EQ(terms.at(s.flat_index({1, j, 2})), -2.0);
    EXPECT_EQ(terms.at(s.flat_index({2, j, 2})), 1.0);
  }
  // The fit recovers the ground truth and Eqs 5.30-5.32 hold to rounding.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int l = 0; l < 3; ++l)
        EXPECT_NEAR(s.control_points[static_cast<Eigen::Index>(s.flat_index({i, j, l}))], rc[i][j][l], 1e-9);
  EXPECT_LT(s.statistics.ss_residual, 1e-18);
}

TEST(ReportV, ConstraintHoldsExactlyWithNoisyData) {
  const auto data = make_design(levels(3, 3, 3), shear_has_data, shear_replicates, 0.02, 3);
  const Surface s = fit_surface(data, rubber_options());
  auto rc = [&](int i, int j, int l) {
    return s.control_points[static_cast<Eigen::Index>(s.flat_index({i, j, l}))];
  };
  for (int j = 0; j < 3; ++j)  // rc_2j2 = -rc_0j2 + 2 rc_1j2
    EXPECT_NEAR(rc(2, j, 2), -rc(0, j, 2) + 2 * rc(1, j, 2), 1e-12 * std::abs(rc(1, j, 2)));
  // The constrained face is linear in amplitude: the middle amplitude lies on the chord.
  const double lo[3] = {0.005, 10.0, 100.0}, mid[3] = {0.025, 10.0, 100.0}, hi[3] = {0.045, 10.0, 100.0};
  EXPECT_NEAR(s.value(mid), 0.5 * (s.value(lo) + s.value(hi)), 1e-10);
  EXPECT_GT(s.statistics.R, 0.99);
  EXPECT_NEAR(s.statistics.s, std::sqrt(s.statistics.ss_residual / 23.0), 1e-15);
}

TEST(ReportV, LoweringTheAmplitudeDegreeInstead) {
  const auto data = make_design(levels(3, 3, 3), shear_has_data, shear_replicates);
  FitOptions o = rubber_options();
  o.missing = MissingCellRemedy::lower_degree;
  const Surface s = fit_surface(data, o);
  EXPECT_EQ(s.axes[0].degree, 1);
  EXPECT_EQ(s.statistics.n_parameters, 18u);  // 2 × 3 × 3
  ASSERT_EQ(s.constraints.size(), 1u);
  EXPECT_EQ(s.constraints[0].origin, "lowered-degree");
  EXPECT_EQ(s.constraints[0].cells.size(), 3u);
}

// More empty cells than occupied ones: local constraints cannot stand in, but lowering a degree
// can: five frequencies, the lowest two at every amplitude and temperature, the other three at one
// corner only (21 cells held, 24 empty); every frequency line through an empty cell holds two
// points, so the frequency's degree goes from 4 to 1. --missing lower-degree was refused with the
// constraints' message before it was tried.
TEST(ReportV, LoweringTheDegreeIsTriedWhenMostCellsAreEmpty) {
  auto lv = levels(3, 3, 3);
  lv[1] = {1.0, 3.0, 10.0, 34.0, 60.0};
  const auto data = make_design(lv, [](const std::vector<int>& i) { return i[1] <= 1 || (i[0] == 0 && i[2] == 0); },
                                [](std::size_t) { return 2; });
  FitOptions o = rubber_options();
  EXPECT_THROW(fit_surface(data, o), fitlib::core::UsageError);  // constrain: more empty than held
  o.missing = MissingCellRemedy::lower_degree;
  const Surface s = fit_surface(data, o);
  EXPECT_EQ(s.axes[1].degree, 1);
  ASSERT_EQ(s.constraints.size(), 1u);
  EXPECT_EQ(s.constraints[0].origin, "lowered-degree");
  EXPECT_EQ(s.constraints[0].cells.size(), 24u);
}

TEST(ReportV, WithoutRemedyMoreUnknownsThanCellsIsAnError) {
  const auto data = make_design(levels(3, 3, 3), shear_has_data, shear_replicates);
  FitOptions o = rubber_options();
  o.missing = MissingCellRemedy::none;
  try {
    fit_surface(data, o);
    FAIL() << "27 unknowns on 24 cells must be refused";
  } catch (const fitlib::core::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("27 unknowns"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("24 distinct"), std::string::npos) << e.what();
  }
}

TEST(ReportV, UserConstraintsReproduceTheAutomaticOnes) {
  const auto data = make_design(levels(3, 3, 3), shear_has_data, shear_replicates, 0.01, 5);
  const Surface automatic = fit_surface(data, rubber_options());
  FitOptions o = rubber_options();
  o.missing = MissingCellRemedy::none;
  o.user_constraints = nlohmann::json::parse(R"({"constraints": [
      {"derivative": {"axis": "strain_amplitude", "order": 2, "at": {"temperature_C": "end"}}}]})");
  const Surface user = fit_surface(data, o);
  EXPECT_EQ(user.statistics.n_parameters, 24u);
  EXPECT_EQ(user.constraints[0].origin, "user");
  EXPECT_LT((user.control_points - automatic.control_points).norm(), 1e-10);

  // The same through explicit terms (Eqs 5.30-5.32 written out).
  nlohmann::json terms = nlohmann::json::array();
  for (int j = 0; j < 3; ++j)
    terms.push_back({{"terms", {{{"index", {2, j, 2}}, {"coefficient", 1}},
                                {{"index", {0, j, 2}}, {"coefficient", 1}},
                                {{"index", {1, j, 2}}, {"coefficient", -2}}}},
                     {"rhs", 0}});
  o.user_constraints = terms;
  const Surface explicit_terms = fit_surface(data, o);
  EXPECT_LT((explicit_terms.control_points - automatic.control_points).norm(), 1e-10);

  o.user_constraints = nlohmann::json::parse(
      R"([{"terms": [{"index": [0,0,0], "coefficient": 1}], "rhs": 1},
          {"terms": [{"index": [0,0,0], "coefficient": 2}], "rhs": 3}])");
  EXPECT_THROW(fit_surface(data, o), fitlib::core::UsageError);
  o.user_constraints = nlohmann::json::parse(R"([{"terms": [{"index": [3,0,0], "coefficient": 1}]}])");
  EXPECT_THROW(fit_surface(data, o), fitlib::core::InputError);
}

// Spec §3.4: N test values, D degrees of freedom, p = N - D from the figure captions.
struct Caption {
  const char* figure;
  int amplitudes, frequencies, temperatures;
  bool shear_missing;  // no test at the largest amplitude with the highest temperature
  int n, dof, p;
};

class CaptionTable : public ::testing::TestWithParam<Caption> {};

TEST_P(CaptionTable, CountsMatch) {
  const Caption c = GetParam();
  const auto lv = levels(c.amplitudes, c.frequencies, c.temperatures);
  const CellFilter has_data = c.shear_missing ? CellFilter(shear_has_data)
                                              : CellFilter([](const std::vector<int>&) { return true; });
  const int cells = c.p;  // one occupied cell per parameter in every captioned design
  // Spread N over the cells: the first N mod cells cells get one extra sample.
  const Replicates replicates = [&](std::size_t cell) {
    return c.n / cells + (static_cast<int>(cell) < c.n % cells ? 1 : 0);
  };
  const Surface s = fit_surface(make_design(lv, has_data, replicates), rubber_options());
  EXPECT_EQ(static_cast<int>(s.statistics.n_points), c.n) << c.figure;
  EXPECT_EQ(static_cast<int>(s.statistics.n_parameters), c.p) << c.figure;
  EXPECT_EQ(static_cast<int>(s.statistics.residual_dof), c.dof) << c.figure;
  EXPECT_EQ(static_cast<int>(s.statistics.n_occupied_cells), cells) << c.figure;
  if (c.dof == 0) {
    EXPECT_TRUE(std::isnan(s.statistics.s)) << "s is undefined without residual dof";
  } else {
    EXPECT_GT(s.statistics.R, 0.9) << c.figure;
  }
}

INSTANTIATE_TEST_SUITE_P(
    FigureCaptions, CaptionTable,
    ::testing::Values(Caption{"6.1 m1 22", 2, 3, 2, false, 36, 24, 12},
                      Caption{"6.3 m1 33", 2, 3, 2, false, 24, 12, 12},
                      Caption{"6.5 m1 12", 3, 3, 3, true, 47, 23, 24},
                      Caption{"6.7 m1 23", 3, 3, 3, true, 42, 18, 24},
                      Caption{"6.9 m2 22", 2, 3, 2, false, 24, 12, 12},
                      Caption{"6.11 m2 33", 2, 3, 2, false, 24, 12, 12},
                      Caption{"6.13 m2 13", 3, 3, 3, true, 42, 18, 24},
                      Caption{"6.15 m2 23", 3, 3, 3, true, 42, 18, 24},
                      Caption{"6.17 m3 11", 2, 3, 2, false, 12, 0, 12},
                      Caption{"6.19 m3 33", 2, 3, 2, false, 12, 0, 12},
                      Caption{"6.21 m3 3232", 2, 3, 2, false, 24, 12, 12},
                      Caption{"6.23 m3 13", 3, 3, 3, true, 24, 0, 24},
                      Caption{"6.25 m3 23", 2, 3, 2, false, 17, 5, 12},
                      Caption{"6.27 m3 2332", 3, 3, 3, true, 42, 18, 24},
                      Caption{"6.29 cord 33", 1, 3, 2, false, 6, 0, 6},
                      Caption{"6.31 cord 32", 2, 3, 3, false, 18, 0, 18},
                      Caption{"6.33 4.2 22", 1, 3, 2, false, 6, 0, 6},
                      Caption{"6.35 4.1 22", 1, 3, 1, false, 3, 0, 3}));

TEST(MissingCells, SingleInteriorCellGetsOneLineConstraint) {
  // Only the centre cell (1,1,1) is empty: a line constraint along amplitude through the middle
  // frequency and temperature levels is cheaper (1 equation) than a face (3 equations).
  const auto data = make_design(levels(3, 3, 3),
                                [](const std::vector<int>& i) { return !(i[0] == 1 && i[1] == 1 && i[2] == 1); },
                                [](std::size_t) { return 2; }, 0.01, 17);
  const Surface s = fit_surface(data, rubber_options());
  EXPECT_EQ(s.statistics.n_parameters, 26u);
  ASSERT_EQ(s.constraints.size(), 1u);
  EXPECT_NE(s.constraints[0].description.find("line through"), std::string::npos) << s.constraints[0].description;
  EXPECT_EQ(s.constraints[0].equations.size(), 1u);
  // Along that line the surface is linear in the amplitude parameter (three collinear points).
  const double f = 34.0, T = s.axes[2].levels[1];
  auto y = [&](double amplitude) {
    const double x[3] = {amplitude, f, T};
    return s.value(x);
  };
  EXPECT_NEAR(y(0.025), 0.5 * (y(0.005) + y(0.045)), 1e-10);  // amplitude parameter 0.5
}

TEST(MissingCells, CornerOfAFullGridInTwoAxesGetsOneEquation) {
  // 3 × 3 levels, corner (2,2) empty: ∂²/∂u² = 0 on the face of the later axis at its end.
  const std::vector<std::vector<double>> lv{{0.005, 0.015, 0.045}, {23.0, 60.0, 100.0}};
  const auto data = make_design(lv, [](const std::vector<int>& i) { return !(i[0] == 2 && i[1] == 2); },
                                [](std::size_t) { return 2; }, 0.01, 3,
                                [](const double* x) { return rubber_storage_MPa(x[0], 10.0, x[1]); });
  FitOptions o;
  o.axes = {{"strain_amplitude", "", {}, {}}, {"temperature_C", "C", {}, {}}};
  const Surface s = fit_surface(data, o);
  EXPECT_EQ(s.statistics.n_parameters, 8u);
  ASSERT_EQ(s.constraints.size(), 1u);
  ASSERT_EQ(s.constraints[0].equations.size(), 1u);
  std::map<std::size_t, double> terms(s.constraints[0].equations[0].terms.begin(),
                                      s.constraints[0].equations[0].terms.end());
  EXPECT_EQ(terms.at(s.flat_index({0, 2})), 1.0);
  EXPECT_EQ(terms.at(s.flat_index({1, 2})), -2.0);
  EXPECT_EQ(terms.at(s.flat_index({2, 2})), 1.0);
}

TEST(MissingCells, TooManyEmptyCellsAreRefused) {
  // Only the diagonal-free corner block holds data: more undetermined than occupied cells.
  const auto data = make_design(levels(3, 3, 3),
                                [](const std::vector<int>& i) { return i[0] + i[1] + i[2] <= 2; },
                                [](std::size_t) { return 2; });
  EXPECT_THROW(fit_surface(data, rubber_options()), fitlib::core::UsageError);
}
