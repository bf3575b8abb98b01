// Fitting, evaluation, hard cases and the JSON/CSV contracts of the surface module.
#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include <Eigen/Dense>
#include <cstdio>
#include <fstream>

#include "designs.hpp"
#include "fitlib/core/error.hpp"

using namespace fitlib::surface;
using namespace fitlib::surface::testing;
using fitlib::core::InputError;
using fitlib::core::NumericalError;
using fitlib::core::UsageError;

namespace {
bool all_cells(const std::vector<int>&) { return true; }
int twice(std::size_t) { return 2; }

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = fitlib_test::temp_path(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}
}  // namespace

TEST(SurfaceFit, FullGridEqualsMonomialLeastSquares) {
  // [DERIVED] spec §3.2: degree-2 Bernstein spans all quadratics, so a full 3×3×3 fit equals a
  // least-squares fit on the 27 monomials u^a v^b w^c, whatever the middle levels.
  const auto data = make_design(levels(3, 3, 3), all_cells, twice, 0.02, 9);
  const Surface s = fit_surface(data, rubber_options());
  EXPECT_EQ(s.statistics.n_parameters, 27u);
  EXPECT_TRUE(s.constraints.empty());
  EXPECT_EQ(s.axes[1].transform, Transform::log10) << "frequency defaults to log10";
  EXPECT_EQ(s.axes[0].transform, Transform::linear);

  const Eigen::Index N = data.x.rows();
  auto params = [&](const double* x, double* u) {
    u[0] = (x[0] - 0.005) / 0.04;
    u[1] = std::log10(x[1] / 3.0) / std::log10(20.0);
    u[2] = (x[2] - 23.0) / 77.0;
  };
  auto monomials = [&](const double* u) {
    Eigen::RowVectorXd row(27);
    int c = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int e = 0; e < 3; ++e) row[c++] = std::pow(u[0], a) * std::pow(u[1], b) * std::pow(u[2], e);
    return row;
  };
  Eigen::MatrixXd M(N, 27);
  for (Eigen::Index r = 0; r < N; ++r) {
    double x[3] = {data.x(r, 0), data.x(r, 1), data.x(r, 2)}, u[3];
    params(x, u);
    M.row(r) = monomials(u);
  }
  const Eigen::VectorXd coef = M.colPivHouseholderQr().solve(data.y);
  fitlib::core::Rng rng(2);
  for (int t = 0; t < 20; ++t) {
    double x[3] = {rng.uniform(0.005, 0.045), std::pow(10.0, rng.uniform(std::log10(3.0), std::log10(60.0))),
                   rng.uniform(23.0, 100.0)};
    double u[3];
    params(x, u);
    EXPECT_NEAR(s.value(x), monomials(u).dot(coef), 1e-9);
  }
  // Statistics by their definitions.
  double ss = 0, st = 0, mean = data.y.mean();
  for (Eigen::Index r = 0; r < N; ++r) {
    double x[3] = {data.x(r, 0), data.x(r, 1), data.x(r, 2)};
    ss += std::pow(data.y[r] - s.value(x), 2);
    st += std::pow(data.y[r] - mean, 2);
  }
  EXPECT_NEAR(s.statistics.ss_residual, ss, 1e-12);
  EXPECT_NEAR(s.statistics.R, std::sqrt(1 - ss / st), 1e-12);
  EXPECT_EQ(s.statistics.residual_dof, static_cast<std::size_t>(N - 27));
}

TEST(SurfaceFit, DegreeAtOrAboveLevelsIsRefusedWithReason) {
  const auto data = make_design(levels(3, 3, 3), all_cells, twice);
  FitOptions o = rubber_options();
  o.axes[2].degree = 3;
  try {
    fit_surface(data, o);
    FAIL();
  } catch (const UsageError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'temperature_C': degree 3 needs at least 4 distinct levels"), std::string::npos) << m;
    EXPECT_NE(m.find("3 level(s) (23, 60, 100)"), std::string::npos) << m;
    EXPECT_NE(m.find("levels - 1"), std::string::npos) << m;
  }
  o.axes[2].degree = kMaxDegree + 1;
  EXPECT_THROW(fit_surface(data, o), UsageError);
}

TEST(SurfaceFit, ExplicitLowerDegreeAndScatteredLevels) {
  // Measured temperatures scatter around their set points (hysteresis): still three levels.
  auto data = make_design(levels(3, 3, 3), all_cells, twice);
  fitlib::core::Rng rng(4);
  for (Eigen::Index r = 0; r < data.x.rows(); ++r) data.x(r, 2) += rng.uniform(-2.0, 2.0);
  FitOptions o = rubber_options();
  o.axes[1].degree = 1;
  const Surface s = fit_surface(data, o);
  EXPECT_EQ(s.axes[2].levels.size(), 3u);
  EXPECT_FALSE(s.axes[2].scattered);
  EXPECT_EQ(s.axes[1].degree, 1);
  EXPECT_EQ(s.statistics.n_parameters, 18u);
}

TEST(SurfaceFit, SingleLevelAxisHasDegreeZero) {
  const auto data = make_design(levels(3, 3, 1), all_cells, twice);
  const Surface s = fit_surface(data, rubber_options());
  EXPECT_EQ(s.axes[2].degree, 0);
  EXPECT_EQ(s.axes[2].start, 60.0);
  EXPECT_EQ(s.axes[2].end, 60.0);
  EXPECT_EQ(s.statistics.n_parameters, 9u);
  const double at[3] = {0.01, 10.0, 60.0};
  const Evaluation e = s.evaluate(at);
  EXPECT_EQ(e.gradient[2], 0.0);
  const double off[3] = {0.01, 10.0, 61.0};
  EXPECT_THROW(s.value(off), InputError);
  bool flagged = false;
  EXPECT_NEAR(s.value(off, true, &flagged), e.value, 1e-12);
  EXPECT_TRUE(flagged);
}

// One point per cell of a full 3×3 grid with degrees 2×2: N = p, the surface interpolates, R = 1
// by construction; the statistics warn (and say so in the JSON). Two points per cell: no warning.
TEST(SurfaceFit, NoResidualDegreesOfFreedomIsAWarning) {
  const auto exact = fit_surface(make_design(levels(3, 3, 1), all_cells, [](std::size_t) { return 1; }, 0.02, 3),
                                 rubber_options());
  ASSERT_EQ(exact.statistics.residual_dof, 0u);
  const auto w = statistics_warnings(exact);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("no residual degrees of freedom (N = 9, p = 9)"), std::string::npos) << w[0];
  EXPECT_EQ(surface_to_json(exact)["statistics"]["warnings"].size(), 1u);
  const auto spare = fit_surface(make_design(levels(3, 3, 1), all_cells, twice, 0.02, 3), rubber_options());
  EXPECT_GT(spare.statistics.residual_dof, 0u);
  EXPECT_TRUE(statistics_warnings(spare).empty());
}

TEST(SurfaceFit, CollinearLevelsAreAnError) {
  SampleSet data;
  data.x.resize(9, 2);
  data.y.resize(9);
  for (int r = 0; r < 9; ++r) {
    data.x(r, 0) = 1.0 + r / 3;       // levels 1, 2, 3
    data.x(r, 1) = 10.0 + 10 * (r / 3);  // moves with the first: 10, 20, 30
    data.y[r] = 1.0 + r;
  }
  FitOptions o;
  o.axes = {{"a", "", Transform::linear, {}}, {"b", "", Transform::linear, {}}};
  try {
    fit_surface(data, o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("collinear"), std::string::npos) << e.what();
  }
  // Scattered data that are collinear: the rank check refuses instead.
  data.x.resize(40, 2);
  data.y.resize(40);
  for (int r = 0; r < 40; ++r) {
    data.x(r, 0) = 1.0 + 0.05 * r;
    data.x(r, 1) = 2.0 * data.x(r, 0);
    data.y[r] = data.x(r, 0) * data.x(r, 0);
  }
  o.axes[0].degree = 2;
  o.axes[1].degree = 2;
  EXPECT_THROW(fit_surface(data, o), NumericalError);
}

TEST(SurfaceFit, DuplicatePointsChangeNotTheSurface) {
  const auto once = make_design(levels(3, 3, 3), shear_has_data, [](std::size_t) { return 1; }, 0.01, 8);
  SampleSet twice_data;
  twice_data.x.resize(2 * once.x.rows(), 3);
  twice_data.x << once.x, once.x;
  twice_data.y.resize(2 * once.y.size());
  twice_data.y << once.y, once.y;
  const Surface a = fit_surface(once, rubber_options());
  const Surface b = fit_surface(twice_data, rubber_options());
  EXPECT_EQ(a.statistics.residual_dof, 0u);
  EXPECT_EQ(b.statistics.n_points, 2 * a.statistics.n_points);
  EXPECT_EQ(b.statistics.n_parameters, 24u);
  EXPECT_LT((a.control_points - b.control_points).norm(), 1e-10 * a.control_points.norm());
}

TEST(SurfaceFit, NonPositiveValueOnLogAxisNamesTheRow) {
  const std::string path = write_temp("surface_log.csv",
                                      "# comment\nstrain_amplitude,frequency_Hz,storage_MPa\n"
                                      "0.005,3,10\n0.015,0,9\n0.045,60,8\n");
  const SampleSet data = read_sample_columns(path, {"strain_amplitude", "frequency_Hz"}, "storage_MPa");
  FitOptions o;
  o.axes = {{"strain_amplitude", "", {}, {}}, {"frequency_Hz", "Hz", {}, {}}};
  try {
    fit_surface(data, o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.column(), 2);
    EXPECT_NE(std::string(e.what()).find(path + ":4:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("log10"), std::string::npos) << e.what();
  }
}

TEST(SurfaceEval, GradientMatchesFiniteDifferences) {
  const auto data = make_design(levels(3, 3, 3), shear_has_data, twice, 0.01, 12);
  const Surface s = fit_surface(data, rubber_options());
  const double x[3] = {0.02, 12.0, 70.0};
  const Evaluation e = s.evaluate(x);
  EXPECT_FALSE(e.extrapolated);
  EXPECT_NEAR(e.value, s.value(x), 1e-14);
  for (int k = 0; k < 3; ++k) {
    double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
    const double h = 1e-6 * x[k];
    xp[k] += h;
    xm[k] -= h;
    EXPECT_NEAR(e.gradient[k], (s.value(xp) - s.value(xm)) / (2 * h), 1e-6 * std::abs(e.gradient[k]) + 1e-9);
  }
}

TEST(SurfaceEval, OutsideTheIntervalIsRefusedUnlessAllowed) {
  const auto data = make_design(levels(3, 3, 3), all_cells, twice);
  const Surface s = fit_surface(data, rubber_options());
  const double inside[3] = {0.045, 60.0, 23.0}, outside[3] = {0.05, 10.0, 50.0};
  EXPECT_NO_THROW(s.value(inside));
  try {
    s.value(outside);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "strain_amplitude");
    EXPECT_NE(std::string(e.what()).find("interpolates only"), std::string::npos);
  }
  const Evaluation e = s.evaluate(outside, true);
  EXPECT_TRUE(e.extrapolated);
  EXPECT_TRUE(std::isfinite(e.value));
}

TEST(SurfaceFit, ScatteredDataRecoverAPolynomial) {
  // 2000 random points of a function inside the degree-(2,3,1) space are reproduced exactly.
  fitlib::core::Rng rng(21);
  SampleSet data;
  data.x.resize(2000, 3);
  data.y.resize(2000);
  auto f = [](double a, double b, double c) { return 1 + a - 2 * a * a + b * b * b * c + 0.5 * c; };
  for (int r = 0; r < 2000; ++r) {
    data.x(r, 0) = rng.uniform(0, 1);
    data.x(r, 1) = rng.uniform(-1, 1);
    data.x(r, 2) = rng.uniform(0, 2);
    data.y[r] = f(data.x(r, 0), data.x(r, 1), data.x(r, 2));
  }
  FitOptions o;
  o.axes = {{"a", "", {}, 2}, {"b", "", {}, 3}, {"c", "", {}, 1}};
  const Surface s = fit_surface(data, o);
  EXPECT_TRUE(s.axes[0].scattered);
  EXPECT_EQ(s.axes[0].level_count, 2000u);
  EXPECT_TRUE(s.axes[0].levels.empty()) << "no per-value level list for scattered axes";
  EXPECT_FALSE(s.level_grid);
  EXPECT_EQ(s.statistics.n_parameters, 24u);
  EXPECT_LT(s.statistics.ss_residual, 1e-20);
  const double x[3] = {0.3, 0.2, 1.1};
  EXPECT_NEAR(s.value(x), f(0.3, 0.2, 1.1), 1e-12);
}

TEST(SurfaceJson, RoundTripKeepsEverything) {
  const auto data = make_design(levels(3, 3, 3), shear_has_data, twice);
  const Surface s = fit_surface(data, rubber_options());
  const std::string path = fitlib_test::temp_path("surface_roundtrip.json");
  save_surface(path, s);
  const Surface back = load_surface(path);
  EXPECT_EQ(back.control_points, s.control_points);
  ASSERT_EQ(back.axes.size(), 3u);
  EXPECT_EQ(back.axes[1].transform, Transform::log10);
  EXPECT_EQ(back.axes[2].start, 23.0);
  EXPECT_EQ(back.constraints.size(), 1u);
  EXPECT_EQ(back.constraints[0].equations.size(), 3u);
  EXPECT_EQ(back.statistics.n_parameters, 24u);
  EXPECT_EQ(back.statistics.R, s.statistics.R);
  EXPECT_EQ(surface_to_json(back), surface_to_json(s));
  const auto j = surface_to_json(s);
  EXPECT_EQ(j["schema"], "fitlib.surface/1");
  EXPECT_EQ(j["statistics"]["residual_dof"], 24);  // 48 points

  auto bad = j;
  bad["control_points"]["values"].erase(0);
  EXPECT_THROW(surface_from_json(bad, "x.json"), InputError);
  bad = j;
  bad["axes"][0]["degree"] = 9;
  EXPECT_THROW(surface_from_json(bad, "x.json"), InputError);
  bad = j;
  bad["axes"][0]["transform"] = "sqrt";
  EXPECT_THROW(surface_from_json(bad, "x.json"), InputError);
  bad = j;
  bad["constraints"][0]["equations"][0]["terms"][0]["index"] = {0, 7};
  EXPECT_THROW(surface_from_json(bad, "x.json"), InputError);
  bad = j;
  bad["axes"][0]["levels"] = "many";
  EXPECT_THROW(surface_from_json(bad, "x.json"), InputError);
}

TEST(SampleColumns, ReadsTheTableConventionsAndNamesBadCells) {
  const std::string ok = write_temp("surface_ok.csv",
                                    "\xEF\xBB\xBF# lab table\r\nmode, x, y, label\r\n"
                                    "shear, 1.5, 2, a\r\n\r\n# between\r\nshear,2.5,3,b\r\n\r\n");
  const SampleSet d = read_sample_columns(ok, {"x"}, "y");
  ASSERT_EQ(d.x.rows(), 2);
  EXPECT_EQ(d.x(1, 0), 2.5);
  EXPECT_EQ(d.y[0], 2.0);
  EXPECT_EQ(d.line_of_row[1], 6);
  EXPECT_EQ(d.column_of_axis[0], 2);

  const std::string bad = write_temp("surface_bad.csv", "x,y\n1,2\n3,abc\n");
  try {
    read_sample_columns(bad, {"x"}, "y");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.column(), 2);
  }
  EXPECT_THROW(read_sample_columns(bad, {"z"}, "y"), InputError);
  const std::string dup = write_temp("surface_dup.csv", "x,x,y\n1,2,3\n");
  EXPECT_THROW(read_sample_columns(dup, {"x"}, "y"), InputError);
  const std::string nan = write_temp("surface_nan.csv", "x,y\n1,nan\n");
  EXPECT_THROW(read_sample_columns(nan, {"x"}, "y"), InputError);
}

namespace {
// A hand-typed storage-modulus table of a filled rubber through its glass transition (moduli over
// three decades): 5 temperatures × 3 frequencies, the (100 °C, 100 Hz) cell optional.
std::string glass_transition_table(bool corner) {
  std::string t = "temperature_C,frequency_Hz,storage_MPa\n"
                  "-20,1,820\n-20,10,1105\n-20,100,1410\n0,1,210\n0,10,330\n0,100,505\n"
                  "23,1,31.2\n23,10,44.8\n23,100,71.5\n60,1,9.8\n60,10,11.1\n60,100,13.9\n"
                  "100,1,7.4\n100,10,7.9\n";
  return corner ? t + "100,100,8.6\n" : t;
}

FitOptions glass_transition_options(Transform dependent) {
  FitOptions o;
  o.axes = {{"temperature_C", "C", Transform::linear, std::nullopt}, {"frequency_Hz", "Hz", Transform::log10, std::nullopt}};
  o.dependent_name = "storage_MPa", o.dependent_unit = "MPa", o.dependent_transform = dependent;
  return o;
}

Surface fit_glass_transition(bool corner, Transform dependent) {
  const std::string path = write_temp(corner ? "glass_full.csv" : "glass_corner.csv", glass_transition_table(corner));
  return fit_surface(read_sample_columns(path, {"temperature_C", "frequency_Hz"}, "storage_MPa"),
                     glass_transition_options(dependent));
}

bool any_contains(const std::vector<std::string>& warnings, const std::string& text) {
  for (const auto& w : warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}
}  // namespace

// Found with a hand-typed table: a degree-4 polynomial in temperature through a glass transition
// passes every point (R = 1) and reaches −33 MPa at 85 °C, 1 Hz, where every measured modulus is
// positive; nothing said so. The range check samples the surface between the levels and warns,
// naming where; fitting log10 of the moduli keeps the surface positive and passes the points too.
TEST(SurfaceFit, ASurfaceThatSwingsOutOfTheDatasRangeIsAWarning) {
  const Surface linear = fit_glass_transition(true, Transform::linear);
  const double at[2] = {85.0, 1.0};
  ASSERT_LT(linear.value(at), 0.0) << "the swing the check must find";
  EXPECT_LE(linear.statistics.surface_min, linear.value(at));
  EXPECT_DOUBLE_EQ(linear.statistics.data_min, 7.4);
  EXPECT_DOUBLE_EQ(linear.statistics.data_max, 1410.0);
  const auto w = statistics_warnings(linear);
  EXPECT_TRUE(any_contains(w, "never change sign")) << w.back();
  EXPECT_TRUE(any_contains(w, "swings between the data")) << w.back();
  EXPECT_TRUE(any_contains(w, "--y storage_MPa:log")) << w.back();
  // The location is the sampled minimum's, in the axes' units: 85 °C and 1 Hz lie on the grid.
  EXPECT_NEAR(linear.statistics.surface_min_at[0], 85.0, 1e-9);
  EXPECT_NEAR(linear.statistics.surface_min_at[1], 1.0, 1e-9);

  const Surface logarithmic = fit_glass_transition(true, Transform::log10);
  EXPECT_GT(logarithmic.value(at), 7.4 * 0.99);
  EXPECT_LT(logarithmic.statistics.max_relative_error, 1e-9) << "still passes every point (N = p)";
  EXPECT_FALSE(any_contains(statistics_warnings(logarithmic), "the surface reaches"));
  EXPECT_GT(logarithmic.statistics.surface_min, 0.0);
  // Constant data: the surface differs from them by round-off only, which is no swing.
  SampleSet flat;
  flat.x.resize(6, 2);
  flat.y = Eigen::VectorXd::Constant(6, 5.0);
  for (int r = 0; r < 6; ++r) flat.x(r, 0) = r / 2, flat.x(r, 1) = r % 2 ? 10.0 : 1.0;
  FitOptions flat_options = glass_transition_options(Transform::linear);
  EXPECT_EQ(range_warning(fit_surface(flat, flat_options)), "");
  // A surface without swings (Report V's full design, degree 2): no range warning.
  const auto quiet = fit_surface(make_design(levels(3, 3, 3), all_cells, twice, 0.02, 9), rubber_options());
  EXPECT_FALSE(any_contains(statistics_warnings(quiet), "the surface reaches"));
  EXPECT_TRUE(std::isfinite(quiet.statistics.surface_min));
}

// Without the (100 °C, 100 Hz) measurement the missing-cell constraint fills that corner with a
// value far outside the data (−415 MPa linear, 5317 MPa as log10): the warning names the empty cell.
TEST(SurfaceFit, AnEmptyCellFilledFarOutsideTheDataIsNamedInTheWarning) {
  for (const Transform t : {Transform::linear, Transform::log10}) {
    const Surface s = fit_glass_transition(false, t);
    ASSERT_EQ(s.missing_cells.size(), 1u);
    const auto w = statistics_warnings(s);
    EXPECT_TRUE(any_contains(w, "empty cell of the level grid (levels 4 2, 0-based)")) << to_string(t);
    const double corner[2] = {100.0, 100.0};
    EXPECT_TRUE(s.value(corner) < 7.4 - 0.25 * (1410 - 7.4) || s.value(corner) > 1410 + 0.25 * (1410 - 7.4));
  }
}

// A log10 dependent: y = 10^(Bezier sum), its gradient ln 10 · y · d(log y)/dx against central
// differences, the JSON keeps the transform (an older file without it reads as linear), and a
// non-positive value is refused at its file line and column.
TEST(SurfaceFit, LogDependentEvaluatesGradientsRoundTripsAndRefusesNonPositiveValues) {
  const Surface s = fit_glass_transition(true, Transform::log10);
  const double x[2] = {40.0, 7.0};
  const Evaluation e = s.evaluate(x);
  EXPECT_DOUBLE_EQ(e.value, s.value(x));
  for (int k = 0; k < 2; ++k) {
    double up[2] = {x[0], x[1]}, down[2] = {x[0], x[1]};
    const double h = 1e-5 * x[k];
    up[k] += h, down[k] -= h;
    EXPECT_NEAR(e.gradient[k], (s.value(up) - s.value(down)) / (2 * h), 1e-6 * std::abs(e.gradient[k])) << k;
  }
  nlohmann::json j = surface_to_json(s);
  EXPECT_EQ(j["dependent"]["transform"], "log10");
  EXPECT_DOUBLE_EQ(surface_from_json(j).value(x), e.value);
  j["dependent"].erase("transform");
  j["statistics"].erase("range");
  const Surface older = surface_from_json(j);
  EXPECT_EQ(older.dependent_transform, Transform::linear);
  EXPECT_FALSE(std::isfinite(older.statistics.surface_min));
  EXPECT_NEAR(std::pow(10.0, older.value(x)), e.value, 1e-9 * e.value);

  const std::string path = write_temp("glass_zero.csv", glass_transition_table(true) + "40,10,0\n");
  try {
    fit_surface(read_sample_columns(path, {"temperature_C", "frequency_Hz"}, "storage_MPa"),
                glass_transition_options(Transform::log10));
    FAIL() << "a zero modulus fitted as log10 must be refused";
  } catch (const InputError& err) {
    EXPECT_EQ(err.line(), 17);
    EXPECT_EQ(err.column(), 3);
    EXPECT_NE(std::string(err.what()).find("not positive, but it is fitted as log10"), std::string::npos) << err.what();
  }
}

// Property over random tables (2 axes, 3–6 levels each, random degrees and values over two decades,
// linear or log10): the range check's extremes are the surface's own values at the places it
// names, inside the interval, no further from the true extremes than a 4× finer sampling finds
// (to 2 % of the range), and a log10 surface never reports a value ≤ 0.
TEST(SurfaceFit, RangeCheckExtremesAreTheSurfacesOwnValuesOnRandomTables) {
  fitlib::core::Rng rng(29);
  for (int trial = 0; trial < 20; ++trial) {
    const int L0 = 3 + static_cast<int>(rng.uniform(0.0, 4.0)), L1 = 3 + static_cast<int>(rng.uniform(0.0, 4.0));
    SampleSet data;
    data.x.resize(L0 * L1, 2);
    data.y.resize(L0 * L1);
    for (int i = 0; i < L0; ++i)
      for (int j = 0; j < L1; ++j) {
        data.x(i * L1 + j, 0) = -20.0 + 100.0 * i / (L0 - 1);
        data.x(i * L1 + j, 1) = std::pow(10.0, 2.0 * j / (L1 - 1));
        data.y[i * L1 + j] = std::pow(10.0, rng.uniform(0.0, 2.0));
      }
    FitOptions o;
    o.axes = {{"temperature_C", "C", Transform::linear, static_cast<int>(rng.uniform(1.0, L0 - 0.01))},
              {"frequency_Hz", "Hz", Transform::log10, static_cast<int>(rng.uniform(1.0, L1 - 0.01))}};
    o.dependent_name = "storage_MPa";
    o.dependent_transform = trial % 2 ? Transform::log10 : Transform::linear;
    const Surface s = fit_surface(data, o);
    const Statistics& st = s.statistics;
    ASSERT_EQ(st.surface_min_at.size(), 2u);
    EXPECT_TRUE(s.contains(st.surface_min_at.data()) && s.contains(st.surface_max_at.data())) << trial;
    EXPECT_NEAR(s.value(st.surface_min_at.data()), st.surface_min, 1e-9 * std::abs(st.surface_max)) << trial;
    EXPECT_NEAR(s.value(st.surface_max_at.data()), st.surface_max, 1e-9 * std::abs(st.surface_max)) << trial;
    double fine_min = INFINITY, fine_max = -INFINITY;
    for (int i = 0; i <= 32 * s.axes[0].degree; ++i)
      for (int j = 0; j <= 32 * s.axes[1].degree; ++j) {
        const double x[2] = {s.axes[0].value_at(double(i) / (32 * s.axes[0].degree)),
                             s.axes[1].value_at(double(j) / (32 * s.axes[1].degree))};
        fine_min = std::min(fine_min, s.value(x, true)), fine_max = std::max(fine_max, s.value(x, true));
      }
    const double range = fine_max - fine_min;
    EXPECT_LE(fine_min, st.surface_min + 1e-12 * range) << trial;
    EXPECT_GE(fine_max, st.surface_max - 1e-12 * range) << trial;
    EXPECT_LT(st.surface_min - fine_min, 0.02 * range) << trial;
    EXPECT_LT(fine_max - st.surface_max, 0.02 * range) << trial;
    if (o.dependent_transform == Transform::log10) EXPECT_GT(st.surface_min, 0.0) << trial;
  }
}
