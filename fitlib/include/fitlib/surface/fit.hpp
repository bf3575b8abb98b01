#pragma once
// Least-squares fitting of Bezier surfaces to measured points (Report V §5.2-5.3):
// levels per axis, the level grid and its empty cells, the remedy for missing cells (local linear
// constraints on control points or a lowered degree, never extra points), user constraints, and
// a rank-revealing QR solve on the constrained control points.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/surface/surface.hpp"

namespace fitlib::surface {

// Measured points: x is N × n (one column per axis), y has N values. `source`, `line_of_row`
// (1-based file lines) and `column_of_axis` / `column_of_y` (1-based) only serve error messages.
struct SampleSet {
  Eigen::MatrixXd x;
  Eigen::VectorXd y;
  std::string source;
  std::vector<int> line_of_row;
  std::vector<int> column_of_axis;
  int column_of_y = 0;
};

struct AxisSpec {
  std::string name;
  std::string unit;
  std::optional<Transform> transform;  // default: default_transform(name)
  std::optional<int> degree;           // default: min(levels - 1, kMaxDegree)
};

// What to do when the level grid has empty cells that no axis's data determine.
enum class MissingCellRemedy {
  constrain,     // local linear constraints ∂^m/∂u_a^m = 0 on the affected face or line (default)
  lower_degree,  // lower one axis's degree globally
  none           // apply nothing (the rank check still refuses an undetermined fit)
};
MissingCellRemedy parse_missing_cell_remedy(const std::string& text);

struct FitOptions {
  std::vector<AxisSpec> axes;
  std::string dependent_name = "y", dependent_unit;
  // log10: fit log10 y (every y must be positive); the surface still evaluates to y.
  Transform dependent_transform = Transform::linear;
  std::string name;
  MissingCellRemedy missing = MissingCellRemedy::constrain;
  // Values of an axis closer than this fraction of its (transformed) range belong to one level.
  // 0: every distinct value is a level.
  double level_tolerance = 0.05;
  // User constraints (docs/surface.md): an array, or {"constraints": [...]}, of
  // {"terms": [{"index": [i, j, l], "coefficient": c}, ...], "rhs": r} or
  // {"derivative": {"axis": NAME, "order": m, "at": {AXIS: "start"|"end"|u}}}.
  nlohmann::json user_constraints;
  std::string user_constraints_source = "constraints";
};

// The level structure of the data along each axis, before fitting.
struct LevelAxis {
  std::vector<double> centres;      // transformed coordinate of each level, ascending
  std::vector<double> upper_bound;  // largest coordinate of each level (for lookup)
  bool scattered = false;
};
std::vector<LevelAxis> find_levels(const SampleSet& data, const std::vector<Transform>& transforms,
                                   double level_tolerance);

Surface fit_surface(const SampleSet& data, const FitOptions& options);

// Constraints ∂^order/∂u_axis^order = 0 for all values of the free parameters, where the axes in
// `fixed` sit at the given Bezier parameters (a face for one fixed axis, a line for all others).
ConstraintGroup derivative_constraints(const Surface& shape, std::size_t axis, int order,
                                       const std::vector<std::pair<std::size_t, double>>& fixed);

// Parses user constraints (see FitOptions::user_constraints) against the surface's axes/degrees.
std::vector<ConstraintGroup> parse_user_constraints(const nlohmann::json& j, const Surface& shape,
                                                    const std::string& source);
// The JSON document of a constraints file; InputError naming the file if it is not valid JSON.
nlohmann::json read_user_constraints(const std::string& path);

// Reads named numeric columns of a CSV with a header row (docs/formats.md §1 conventions: `#` comments,
// BOM, CRLF, spaces after commas, trailing empty line). InputError names file:line:column.
SampleSet read_sample_columns(const std::string& path, const std::vector<std::string>& x_columns,
                              const std::string& y_column);

}  // namespace fitlib::surface
