// Least-squares fit of a Bezier surface (Report V §5.2-5.3; docs/surface.md). Missing cells of
// the level grid: level_grid.cpp.
//
// Solve: constraints C c = r are eliminated by a null-space basis Z (c = c0 + Z z); the rows of
// [A Z | y - A c0] are reduced chunk by chunk with Householder QR into a small triangle (memory
// independent of N beyond the data themselves), which is then solved by column-pivoting QR to
// reveal the rank.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/surface/bernstein.hpp"
#include "fitlib/surface/fit.hpp"
#include "level_grid.hpp"

namespace fitlib::surface {

MissingCellRemedy parse_missing_cell_remedy(const std::string& text) {
  if (text == "constrain") return MissingCellRemedy::constrain;
  if (text == "lower-degree") return MissingCellRemedy::lower_degree;
  if (text == "none") return MissingCellRemedy::none;
  throw core::UsageError("unknown missing-cell remedy '" + text +
                         "' (use constrain, lower-degree or none)");
}

namespace {

constexpr Eigen::Index kChunkRows = 4096;
constexpr double kRankThreshold = 1e-10;

std::string where_row(const SampleSet& d, Eigen::Index r) {
  return d.line_of_row.empty() ? "row " + std::to_string(r + 1) + ": " : std::string();
}

int line_of(const SampleSet& d, Eigen::Index r) {
  return d.line_of_row.empty() ? 0 : d.line_of_row[static_cast<std::size_t>(r)];
}

int column_of(const SampleSet& d, Eigen::Index k) {
  return d.column_of_axis.empty() ? 0 : d.column_of_axis[static_cast<std::size_t>(k)];
}

void validate(const SampleSet& d, const std::vector<Axis>& axes) {
  for (Eigen::Index r = 0; r < d.x.rows(); ++r) {
    for (Eigen::Index k = 0; k < d.x.cols(); ++k) {
      const double x = d.x(r, k);
      const Axis& a = axes[static_cast<std::size_t>(k)];
      if (!std::isfinite(x))
        throw core::InputError(where_row(d, r) + "'" + a.name + "' is not a finite number",
                               d.source, line_of(d, r), column_of(d, k));
      if (a.transform == Transform::log10 && !(x > 0.0)) {
        std::ostringstream msg;
        msg << where_row(d, r) << "'" << a.name << "' = " << x
            << " is not positive, but the axis is log10 (use :lin for a linear axis)";
        throw core::InputError(msg.str(), d.source, line_of(d, r), column_of(d, k));
      }
    }
    if (!std::isfinite(d.y[r]))
      throw core::InputError(where_row(d, r) + "the dependent value is not a finite number",
                             d.source, line_of(d, r), d.column_of_y);
  }
}

// log10 y, the values a log10 dependent's control points describe (each y > 0, else InputError at
// its cell).
Eigen::VectorXd log10_values(const SampleSet& d) {
  for (Eigen::Index r = 0; r < d.y.size(); ++r)
    if (!(d.y[r] > 0.0)) {
      std::ostringstream msg;
      msg << where_row(d, r) << "the dependent value " << d.y[r]
          << " is not positive, but it is fitted as log10 (drop :log from --y for a linear fit)";
      throw core::InputError(msg.str(), d.source, line_of(d, r), d.column_of_y);
    }
  return d.y.array().log10().matrix();
}

// Basis row φ_j(x) = Π_k B_{i_k}(u_k) for all flat j, built axis by axis in place.
void basis_row(const Surface& s, const double* u, double* phi, double* b) {
  std::size_t length = 1;
  phi[0] = 1.0;
  for (std::size_t k = 0; k < s.axes.size(); ++k) {
    const int d = s.axes[k].degree;
    bernstein(d, u[k], b);
    const std::size_t width = static_cast<std::size_t>(d + 1);
    for (std::size_t q = length; q-- > 0;) {
      const double v = phi[q];
      for (std::size_t l = width; l-- > 0;) phi[q * width + l] = v * b[l];
    }
    length *= width;
  }
}

std::size_t count_distinct_cells(const std::vector<std::int32_t>& level_index, std::size_t n,
                                 std::size_t rows) {
  std::vector<std::size_t> order(rows);
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](std::size_t x, std::size_t y) {
    return std::lexicographical_compare(&level_index[x * n], &level_index[x * n] + n,
                                        &level_index[y * n], &level_index[y * n] + n);
  };
  std::sort(order.begin(), order.end(), less);
  std::size_t distinct = rows ? 1 : 0;
  for (std::size_t i = 1; i < rows; ++i) distinct += less(order[i - 1], order[i]);
  return distinct;
}

// Axes named as asked, with their transforms (default by name when not given).
Surface described_surface(const FitOptions& options) {
  Surface s;
  s.name = options.name;
  s.dependent_name = options.dependent_name;
  s.dependent_unit = options.dependent_unit;
  s.dependent_transform = options.dependent_transform;
  for (const auto& spec : options.axes) {
    Axis a;
    a.name = spec.name;
    a.unit = spec.unit;
    a.transform = spec.transform.value_or(default_transform(spec.name));
    s.axes.push_back(a);
  }
  return s;
}

// The degree asked for an axis with L levels: at most L − 1 (Report V §5.2), else UsageError
// listing the levels; without a request min(L − 1, kMaxDegree).
int axis_degree(const Axis& a, const std::optional<int>& requested, int L, double level_tolerance) {
  if (!requested) return std::min(L - 1, kMaxDegree);
  const int d = *requested;
  if (d < 0 || d > kMaxDegree)
    throw core::UsageError("axis '" + a.name + "': degree " + std::to_string(d) + " is outside 0.." +
                           std::to_string(kMaxDegree));
  if (d <= L - 1) return d;
  std::ostringstream msg;
  msg << "axis '" << a.name << "': degree " << d << " needs at least " << d + 1
      << " distinct levels, but the data hold " << L << " level(s)";
  if (!a.levels.empty() && L <= 10) {
    msg << " (";
    for (int l = 0; l < L; ++l) msg << (l ? ", " : "") << a.levels[static_cast<std::size_t>(l)];
    msg << ")";
  }
  msg << "; the degree of an axis is at most its number of test levels - 1 (Report V §5.2), "
         "otherwise the surface is not determined between the levels. Values closer than "
      << level_tolerance << " of the axis range form one level.";
  throw core::UsageError(msg.str());
}

// Interval from the data, levels and degree of every axis.
void set_axes_from_data(Surface& s, const SampleSet& data, const std::vector<LevelAxis>& levels,
                        const FitOptions& options) {
  for (std::size_t k = 0; k < s.axes.size(); ++k) {
    Axis& a = s.axes[k];
    a.start = data.x.col(static_cast<Eigen::Index>(k)).minCoeff();
    a.end = data.x.col(static_cast<Eigen::Index>(k)).maxCoeff();
    a.scattered = levels[k].scattered;
    a.level_count = levels[k].centres.size();
    if (!a.scattered)
      for (double c : levels[k].centres)
        a.levels.push_back(a.transform == Transform::log10 ? std::pow(10.0, c) : c);
    a.degree = axis_degree(a, options.axes[k].degree, static_cast<int>(levels[k].centres.size()),
                           options.level_tolerance);
  }
}

// Level index of every row and axis (row-major, n per row).
std::vector<std::int32_t> level_indices(const Surface& s, const SampleSet& data, const std::vector<LevelAxis>& levels) {
  const Eigen::Index N = data.x.rows();
  const std::size_t n = s.axes.size();
  std::vector<std::int32_t> level_index(static_cast<std::size_t>(N) * n);
  for (Eigen::Index r = 0; r < N; ++r)
    for (std::size_t k = 0; k < n; ++k) {
      const double c = s.axes[k].coordinate(data.x(r, static_cast<Eigen::Index>(k)));
      const auto& ub = levels[k].upper_bound;
      level_index[static_cast<std::size_t>(r) * n + k] =
          static_cast<std::int32_t>(std::lower_bound(ub.begin(), ub.end(), c) - ub.begin());
    }
  return level_index;
}

// The control points that satisfy the constraints C c = r: c = c0 + Z z with q free z.
struct ConstrainedBasis {
  bool constrained = false;
  Eigen::MatrixXd Z;
  Eigen::VectorXd c0;
  Eigen::Index q = 0;
};

ConstrainedBasis constrained_basis(const Surface& s) {
  const Eigen::Index p = static_cast<Eigen::Index>(s.size());
  Eigen::Index n_constraints = 0;
  for (const auto& g : s.constraints) n_constraints += static_cast<Eigen::Index>(g.equations.size());
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n_constraints, p);
  Eigen::VectorXd rhs(n_constraints);
  Eigen::Index row = 0;
  for (const auto& g : s.constraints)
    for (const auto& e : g.equations) {
      for (const auto& [flat, coefficient] : e.terms) C(row, static_cast<Eigen::Index>(flat)) += coefficient;
      rhs[row++] = e.rhs;
    }
  ConstrainedBasis basis;
  basis.c0 = Eigen::VectorXd::Zero(p);
  basis.q = p;
  basis.constrained = n_constraints > 0;
  if (!basis.constrained) return basis;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(C.transpose());
  qr.setThreshold(1e-12);
  const Eigen::Index rank = qr.rank();
  const Eigen::MatrixXd Q = qr.householderQ();
  basis.Z = Q.rightCols(p - rank);
  basis.q = p - rank;
  basis.c0 = C.completeOrthogonalDecomposition().solve(rhs);
  if ((C * basis.c0 - rhs).norm() > 1e-9 * (1.0 + rhs.norm()))
    throw core::UsageError("the constraints on the control points contradict each other");
  return basis;
}

// Chunked Householder reduction of [A Z | y − A c0] to a (q+1)×(q+1) triangle; `y` the values the
// control points describe (data.y, or its log10).
Eigen::MatrixXd reduced_triangle(const Surface& s, const SampleSet& data, const Eigen::VectorXd& y,
                                 const ConstrainedBasis& basis) {
  const Eigen::Index N = data.x.rows(), q = basis.q, p = static_cast<Eigen::Index>(s.size());
  const std::size_t n = s.axes.size();
  Eigen::MatrixXd R_aug = Eigen::MatrixXd::Zero(q + 1, q + 1);
  std::vector<double> u(n), phi(static_cast<std::size_t>(p)), b(kMaxDegree + 1);
  Eigen::MatrixXd block(std::min<Eigen::Index>(N, kChunkRows) + q + 1, q + 1);
  for (Eigen::Index first = 0; first < N; first += kChunkRows) {
    const Eigen::Index rows = std::min<Eigen::Index>(kChunkRows, N - first);
    block.resize(rows + q + 1, q + 1);
    block.topRows(q + 1) = R_aug;
    for (Eigen::Index r = 0; r < rows; ++r) {
      const Eigen::Index row = first + r;
      for (std::size_t k = 0; k < n; ++k) u[k] = s.axes[k].parameter(data.x(row, static_cast<Eigen::Index>(k)));
      basis_row(s, u.data(), phi.data(), b.data());
      const Eigen::Map<const Eigen::RowVectorXd> phi_row(phi.data(), p);
      if (basis.constrained) {
        block.row(q + 1 + r).head(q) = phi_row * basis.Z;
        block(q + 1 + r, q) = y[row] - phi_row.dot(basis.c0);
      } else {
        block.row(q + 1 + r).head(q) = phi_row;
        block(q + 1 + r, q) = y[row];
      }
    }
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(block);
    R_aug = qr.matrixQR().topRows(q + 1).triangularView<Eigen::Upper>();
  }
  return R_aug;
}

// Least-squares control points; NumericalError for a rank-deficient design.
Eigen::VectorXd control_points(const Surface& s, const SampleSet& data, const Eigen::VectorXd& y,
                               const ConstrainedBasis& basis) {
  const Eigen::Index q = basis.q;
  const Eigen::MatrixXd R_aug = reduced_triangle(s, data, y, basis);
  const Eigen::MatrixXd R = R_aug.topLeftCorner(q, q);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> solver(R);
  solver.setThreshold(kRankThreshold);
  if (solver.rank() < q) {
    std::ostringstream msg;
    msg << "the data determine only " << solver.rank() << " of the surface's " << q
        << " free control-point combinations (rank-deficient design";
    if (!s.missing_cells.empty()) msg << "; " << s.missing_cells.size() << " empty cell(s)";
    msg << "): lower a degree (--degree), add constraints or add data at other levels";
    throw core::NumericalError(msg.str());
  }
  const Eigen::VectorXd z = solver.solve(R_aug.col(q).head(q));
  return basis.constrained ? Eigen::VectorXd(basis.c0 + basis.Z * z) : z;
}

// The surface's extremes over its interval, sampled on m_k + 1 equidistant parameters per axis,
// m_k = f·d_k with f the largest of 8, 4, 2, 1 that keeps the grid within kRangeSamples points
// (at most ~15 ms; a degree-d polynomial swings at most d − 1 times, and 8 samples per degree find
// the swings of interest). Too many axes for even f = 1: not sampled (NaN).
constexpr double kRangeSamples = 5e4;
void sample_range(Surface& s) {
  const std::size_t n = s.axes.size();
  std::vector<int> m(n);
  for (const int factor : {8, 4, 2, 1}) {
    double points = 1.0;
    for (std::size_t k = 0; k < n; ++k) m[k] = factor * s.axes[k].degree, points *= m[k] + 1;
    if (points <= kRangeSamples) break;
    if (factor == 1) return;
  }
  Statistics& st = s.statistics;
  std::vector<int> i(n, 0);
  std::vector<double> u(n);
  st.surface_min = std::numeric_limits<double>::infinity(), st.surface_max = -st.surface_min;
  std::vector<double> u_min(n), u_max(n);
  for (;;) {
    for (std::size_t k = 0; k < n; ++k) u[k] = m[k] ? double(i[k]) / m[k] : 0.0;
    const double y = dependent_value(s, evaluate_at_parameters(s, u.data(), nullptr));
    if (y < st.surface_min) st.surface_min = y, u_min = u;
    if (y > st.surface_max) st.surface_max = y, u_max = u;
    std::size_t k = n;  // odometer, last axis fastest
    while (k-- > 0 && ++i[k] > m[k]) i[k] = 0;
    if (k == std::size_t(-1)) break;
  }
  st.surface_min_at.resize(n), st.surface_max_at.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    st.surface_min_at[k] = s.axes[k].value_at(u_min[k]), st.surface_max_at[k] = s.axes[k].value_at(u_max[k]);
}

// Statistics (Report V §5.2): N, p, dof, R, s, maximum relative error — of y itself, also for a
// log10 dependent —, and the range check (sample_range).
void fill_statistics(Surface& s, const SampleSet& data, Eigen::Index q, std::size_t occupied) {
  const Eigen::Index N = data.x.rows();
  const std::size_t n = s.axes.size();
  Statistics& st = s.statistics;
  st.n_points = static_cast<std::size_t>(N);
  st.n_parameters = static_cast<std::size_t>(q);
  st.residual_dof = st.n_points - st.n_parameters;
  st.n_occupied_cells = occupied;
  const double mean = data.y.mean();
  std::vector<double> u(n);
  for (Eigen::Index r = 0; r < N; ++r) {
    for (std::size_t k = 0; k < n; ++k) u[k] = s.axes[k].parameter(data.x(r, static_cast<Eigen::Index>(k)));
    const double residual = data.y[r] - dependent_value(s, evaluate_at_parameters(s, u.data(), nullptr));
    st.ss_residual += residual * residual;
    st.ss_total += (data.y[r] - mean) * (data.y[r] - mean);
    if (data.y[r] != 0.0) {
      const double relative = std::abs(residual / data.y[r]);
      if (relative > st.max_relative_error) {
        st.max_relative_error = relative;
        st.max_relative_error_row = static_cast<std::size_t>(r);
      }
    }
  }
  st.R = st.ss_total > 0.0 ? std::sqrt(std::max(0.0, 1.0 - st.ss_residual / st.ss_total))
                           : std::numeric_limits<double>::quiet_NaN();
  st.s = st.residual_dof > 0 ? std::sqrt(st.ss_residual / double(st.residual_dof))
                             : std::numeric_limits<double>::quiet_NaN();
  st.data_min = data.y.minCoeff(), st.data_max = data.y.maxCoeff();
  sample_range(s);
}

}  // namespace

Surface fit_surface(const SampleSet& data, const FitOptions& options) {
  const Eigen::Index N = data.x.rows();
  const std::size_t n = static_cast<std::size_t>(data.x.cols());
  if (options.axes.size() != n || n == 0)
    throw core::UsageError("the surface needs one axis description per data column (" +
                           std::to_string(n) + " columns, " + std::to_string(options.axes.size()) +
                           " axes)");
  if (N == 0) throw core::InputError("no data rows to fit", data.source);
  if (data.y.size() != N) throw core::UsageError("x and y hold different numbers of rows");
  if (!(options.level_tolerance >= 0.0 && options.level_tolerance < 1.0))
    throw core::UsageError("level tolerance must lie in [0, 1)");

  Surface s = described_surface(options);
  validate(data, s.axes);
  std::vector<Transform> transforms;
  for (const auto& a : s.axes) transforms.push_back(a.transform);
  const auto levels = find_levels(data, transforms, options.level_tolerance);
  set_axes_from_data(s, data, levels, options);
  const auto level_index = level_indices(s, data, levels);

  if (const auto grid = detail::level_grid(s, levels, level_index)) {
    s.level_grid = true;
    detail::check_collinear(s, *grid, data.source);
    detail::remedy_missing_cells(s, *grid, levels, options);
  }
  for (auto& group : parse_user_constraints(options.user_constraints, s, options.user_constraints_source))
    s.constraints.push_back(std::move(group));

  const ConstrainedBasis basis = constrained_basis(s);
  const std::size_t occupied = count_distinct_cells(level_index, n, static_cast<std::size_t>(N));
  if (static_cast<std::size_t>(basis.q) > occupied) {
    std::ostringstream msg;
    msg << "the surface has " << basis.q << " unknowns (control points";
    if (basis.constrained) msg << " after " << (static_cast<Eigen::Index>(s.size()) - basis.q) << " constraint(s)";
    msg << ") but the data occupy only " << occupied
        << " distinct level combinations (cells); lower a degree (--degree) or add constraints";
    throw core::UsageError(msg.str());
  }
  s.control_points = control_points(
      s, data, options.dependent_transform == Transform::log10 ? log10_values(data) : data.y, basis);
  fill_statistics(s, data, basis.q, occupied);
  return s;
}

}  // namespace fitlib::surface
