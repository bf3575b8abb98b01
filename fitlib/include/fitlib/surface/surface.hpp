#pragma once
// Bezier tensor-product hyper-surfaces of measured data (Report V §5; spec
// docs/surface.md; JSON per docs/formats.md §4).
//
//   y(x_1..x_n) = Σ c_{i_1..i_n} B_{i_1,d_1}(u_1) ... B_{i_n,d_n}(u_n),
//   u_k = (T_k(x_k) - T_k(start_k)) / (T_k(end_k) - T_k(start_k)),  T_k = identity or log10.
//
// The independent variables use equidistant control points, so each u_k is this linear map of the
// (transformed) variable (Eqs 5.19-5.23). Only the control points c of the dependent variable are
// fitted. Control points are stored row-major over the multi-index (first axis slowest, last axis
// fastest), i.e. c_{ijl} at ((i (d_2+1) + j) (d_3+1) + l), as Report V writes rc_{ijl}.
#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fitlib::surface {

// Highest degree per axis (the default degree is levels - 1, capped here). Seven levels per axis
// is more than any lab design of Report V, and higher Bernstein degrees over scattered data only
// follow the noise (bench_surface: accuracy versus degree).
constexpr int kMaxDegree = 6;
// A surface has at most this many axes and control points (the count must not wrap around).
constexpr std::size_t kMaxAxes = 16;
constexpr double kMaxControlPoints = 1e7;

enum class Transform { linear, log10 };
const char* to_string(Transform t);
// "linear"|"lin" or "log10"|"log"; UsageError otherwise.
Transform parse_transform(const std::string& text);
// The default transform for a variable of this name: log10 for frequencies (a name containing
// "frequency", as frequency_Hz and angular_frequency_rad_s), linear otherwise. See docs/surface.md.
Transform default_transform(const std::string& axis_name);

struct Axis {
  std::string name;
  std::string unit;
  Transform transform = Transform::linear;
  double start = 0.0, end = 1.0;  // interval in the variable's own units (from the data)
  int degree = 0;
  std::vector<double> levels;  // level centres found in the data, own units (empty if scattered)
  std::size_t level_count = 0; // number of levels (distinct values if scattered)
  bool scattered = false;      // values did not form levels (each distinct value is a level)

  // The transformed coordinate T(x); InputError for x <= 0 on a log10 axis.
  double coordinate(double x) const;
  // The Bezier parameter u(x); 0 for a degenerate (single-value) interval.
  double parameter(double x) const;
  // du/dx at x.
  double parameter_derivative(double x) const;
  // x lies in [start, end] (with a relative tolerance of 1e-9 of the interval).
  bool contains(double x) const;
  // The variable's value at Bezier parameter u (the inverse of parameter()).
  double value_at(double u) const;
  // The index of the level nearest to x in the transformed coordinate (0 when levels is empty).
  int nearest_level(double x) const;
};

// One linear equation Σ coefficient · c[index] = rhs on the control points (flat indices).
struct LinearConstraint {
  std::vector<std::pair<std::size_t, double>> terms;
  double rhs = 0.0;
};

// Constraints applied together, with why: "missing-cells" (chosen by the fit), "user" (given).
struct ConstraintGroup {
  std::string origin;
  std::string description;
  std::vector<LinearConstraint> equations;
  std::vector<std::vector<int>> cells;  // empty cells (level indices per axis) it accounts for
};

struct Statistics {
  std::size_t n_points = 0;      // N
  std::size_t n_parameters = 0;  // p: free control-point combinations after constraints
  std::size_t residual_dof = 0;  // N - p
  double R = std::numeric_limits<double>::quiet_NaN();  // multiple correlation coefficient
  double s = std::numeric_limits<double>::quiet_NaN();  // residual standard deviation (NaN if dof 0)
  double max_relative_error = 0.0;                      // max |y - ŷ| / |y| over rows with y != 0
  std::size_t max_relative_error_row = 0;               // 0-based data row where it occurs
  double ss_residual = 0.0, ss_total = 0.0;
  std::size_t n_occupied_cells = 0;  // distinct level combinations holding data
  // The data's values and the surface's extremes over its whole interval, sampled on a grid finer
  // than the levels (NaN when not sampled): a fit can pass every point and swing between them.
  double data_min = std::numeric_limits<double>::quiet_NaN(), data_max = data_min;
  double surface_min = data_min, surface_max = data_min;
  std::vector<double> surface_min_at, surface_max_at;  // where, in the axes' own units
};

class Surface;
// Warnings on the statistics (docs/surface.md "Statistics"): no residual degrees of freedom — the
// surface passes through every point whatever it is between them, R and s say nothing —, and a
// surface that changes sign where the data do not or leaves the data's range by more than
// kRangeOvershoot of it between the data.
constexpr double kRangeOvershoot = 0.25;
std::vector<std::string> statistics_warnings(const Surface& s);
// The range check's warning alone ("" when the surface keeps to the data's sign and range).
std::string range_warning(const Surface& s);

struct Evaluation {
  double value = 0.0;
  Eigen::VectorXd gradient;   // dy/dx_k in the variables' own units
  bool extrapolated = false;  // some x_k lay outside its interval (only with allow_extrapolation)
};

class Surface {
 public:
  static constexpr const char* kSchema = "fitlib.surface/1";

  std::string name;
  std::string dependent_name, dependent_unit;
  // log10: the control points describe log10 y (moduli spanning decades); value() returns y.
  Transform dependent_transform = Transform::linear;
  std::vector<Axis> axes;
  Eigen::VectorXd control_points;
  std::vector<ConstraintGroup> constraints;
  std::vector<std::vector<int>> missing_cells;  // empty cells of the level grid
  bool level_grid = false;                      // the missing-cell analysis ran
  Statistics statistics;
  nlohmann::json provenance = nlohmann::json::object();

  std::size_t dimension() const { return axes.size(); }
  std::size_t size() const;  // Π (d_k + 1)
  std::size_t flat_index(const std::vector<int>& multi_index) const;
  std::vector<int> multi_index(std::size_t flat) const;

  // Value at x[0..n-1]. Outside the interval: InputError naming the axis unless
  // allow_extrapolation; `extrapolated` (if given) tells whether it was outside.
  double value(const double* x, bool allow_extrapolation = false,
               bool* extrapolated = nullptr) const;
  Evaluation evaluate(const double* x, bool allow_extrapolation = false) const;
  bool contains(const double* x) const;
};

// Value and gradient at Bezier parameters u[0..n-1] (no interval check); `gradient` may be null
// and then receives dy/du_k. Both of the control points' quantity: log10 y for a log10 dependent.
double evaluate_at_parameters(const Surface& s, const double* u, double* gradient_du);
// y from the control points' quantity (10^v for a log10 dependent).
double dependent_value(const Surface& s, double v);

nlohmann::json surface_to_json(const Surface& s);
// Validates as it reads; InputError names the source and key.
Surface surface_from_json(const nlohmann::json& j, const std::string& source = "surface");
Surface load_surface(const std::string& path);
// A control-point index of `s` read from JSON: one whole number per axis, each in [0, degree];
// InputError naming `source` and `key` otherwise (a float beyond int's range included).
std::vector<int> control_point_index_from_json(const nlohmann::json& index, const Surface& s,
                                               const std::string& source, const std::string& key);
void save_surface(const std::string& path, const Surface& s);

}  // namespace fitlib::surface
