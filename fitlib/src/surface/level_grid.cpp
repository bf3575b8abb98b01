// Missing cells: the level grid of the data is built; an empty cell is "determined by the data"
// when, along some axis a, the line through it holds at least d_a + 1 occupied levels (the curve
// along a there is fixed by data and the cell is interpolated). Every other empty cell needs a
// remedy: by default local constraints ∂^m/∂u_a^m = 0 (m = occupied levels on the line) on a face
// (one other axis fixed at a level) or a line (all others fixed), chosen greedily with the fewest
// constraints per empty cell; faces win ties over lines, then the face of the later axis (Report V
// fixes the temperature face and makes the amplitude direction linear, Eqs 5.26-5.32). Missing
// cells are never "compensated" by points elsewhere.
#include "level_grid.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "fitlib/core/error.hpp"

namespace fitlib::surface::detail {
namespace {

constexpr std::size_t kMaxGridCells = 1000000;

// A candidate remedy: ∂^order/∂u_a^order = 0 on a face (fixed grid axis b at level) or on the
// line through `cell`.
struct Remedy {
  bool face = false;
  std::size_t a = 0, b = 0, level = 0, cell = 0;
  int order = 0;
  std::size_t n_constraints = 0;
  std::vector<std::size_t> covers;
};

double level_parameter(const Axis& axis, const LevelAxis& levels, std::size_t l) {
  // End levels sit on the faces u = 0 and u = 1 (Report V's "third level" is w = 1).
  if (l == 0) return 0.0;
  if (l + 1 == levels.centres.size()) return 1.0;
  const double c0 = axis.coordinate(axis.start), c1 = axis.coordinate(axis.end);
  return (levels.centres[l] - c0) / (c1 - c0);
}

std::string cell_text(const Surface& s, const Grid& grid, std::size_t cell) {
  const auto index = grid.unflatten(cell);
  std::ostringstream out;
  out.precision(6);
  out << "(";
  for (std::size_t g = 0; g < grid.axes.size(); ++g) {
    const Axis& a = s.axes[grid.axes[g]];
    out << (g ? ", " : "") << a.name << " = " << a.levels[static_cast<std::size_t>(index[g])];
  }
  return out.str() + ")";
}

// Returns the empty cells that no axis's data determine under the current degrees.
std::vector<std::size_t> undetermined_cells(const Surface& s, const Grid& grid,
                                            const std::vector<std::size_t>& empty) {
  std::vector<std::size_t> result;
  for (std::size_t cell : empty) {
    bool determined = false;
    for (std::size_t g = 0; g < grid.axes.size() && !determined; ++g)
      determined = grid.occupied_on_line(cell, g) >= s.axes[grid.axes[g]].degree + 1;
    if (!determined) result.push_back(cell);
  }
  return result;
}

std::size_t product_of_other_degrees(const Surface& s, const std::vector<std::size_t>& excluded) {
  std::size_t p = 1;
  for (std::size_t k = 0; k < s.axes.size(); ++k)
    if (std::find(excluded.begin(), excluded.end(), k) == excluded.end())
      p *= static_cast<std::size_t>(s.axes[k].degree + 1);
  return p;
}

std::vector<Remedy> candidate_remedies(const Surface& s, const Grid& grid,
                                       const std::vector<std::size_t>& open) {
  std::vector<Remedy> candidates;
  const std::size_t G = grid.axes.size();
  std::vector<std::size_t> grid_axes_all = grid.axes;
  for (std::size_t ga = 0; ga < G; ++ga) {
    const std::size_t a = grid.axes[ga];
    const int d = s.axes[a].degree;
    if (d < 1) continue;
    // faces: grid axis gb fixed at level l
    for (std::size_t gb = 0; gb < G; ++gb) {
      if (gb == ga) continue;
      for (std::size_t l = 0; l < grid.levels[gb]; ++l) {
        int m = d + 1;
        for (std::size_t cell = 0; cell < grid.cells(); ++cell) {
          if ((cell / grid.strides[gb]) % grid.levels[gb] != l) continue;
          if ((cell / grid.strides[ga]) % grid.levels[ga] != 0) continue;  // one cell per line
          m = std::min(m, grid.occupied_on_line(cell, ga));
        }
        if (m < 1 || m > d) continue;
        Remedy r;
        r.face = true;
        r.a = a;
        r.b = grid.axes[gb];
        r.level = l;
        r.order = m;
        r.n_constraints = static_cast<std::size_t>(d - m + 1) * product_of_other_degrees(s, {a, r.b});
        for (std::size_t cell : open)
          if ((cell / grid.strides[gb]) % grid.levels[gb] == l) r.covers.push_back(cell);
        if (!r.covers.empty()) candidates.push_back(std::move(r));
      }
    }
    // lines through each open cell (all other grid axes fixed); for two grid axes these are faces
    if (G < 3) continue;
    for (std::size_t cell : open) {
      const int m = grid.occupied_on_line(cell, ga);
      if (m < 1 || m > d) continue;
      Remedy r;
      r.a = a;
      r.cell = cell;
      r.order = m;
      r.n_constraints = static_cast<std::size_t>(d - m + 1) * product_of_other_degrees(s, grid_axes_all);
      const std::size_t base = cell - ((cell / grid.strides[ga]) % grid.levels[ga]) * grid.strides[ga];
      for (std::size_t other : open)
        if (other - ((other / grid.strides[ga]) % grid.levels[ga]) * grid.strides[ga] == base)
          r.covers.push_back(other);
      candidates.push_back(std::move(r));
    }
  }
  return candidates;
}

// Fewest constraints per covered cell; then more cells; faces before lines; the face of the later
// axis; the earlier derivative axis.
bool better(const Remedy& x, const Remedy& y) {
  const double cx = double(x.n_constraints) / double(x.covers.size());
  const double cy = double(y.n_constraints) / double(y.covers.size());
  if (cx != cy) return cx < cy;
  if (x.covers.size() != y.covers.size()) return x.covers.size() > y.covers.size();
  if (x.face != y.face) return x.face;
  if (x.b != y.b) return x.b > y.b;
  return x.a < y.a;
}

void constrain_missing_cells(Surface& s, const Grid& grid, const std::vector<LevelAxis>& levels,
                             std::vector<std::size_t> open) {
  while (!open.empty()) {
    const auto candidates = candidate_remedies(s, grid, open);
    if (candidates.empty()) {
      std::ostringstream msg;
      msg << open.size() << " empty cell(s) of the level grid, e.g. " << cell_text(s, grid, open[0])
          << ", have no data on any line through them, so no local constraint can stand in for "
             "them (Report V §5.3); lower a degree (--degree) or supply constraints";
      throw core::UsageError(msg.str());
    }
    const Remedy& best = *std::min_element(candidates.begin(), candidates.end(), better);
    std::vector<std::pair<std::size_t, double>> fixed;
    std::string where;
    if (best.face) {
      const std::size_t gb = static_cast<std::size_t>(
          std::find(grid.axes.begin(), grid.axes.end(), best.b) - grid.axes.begin());
      fixed.emplace_back(best.b, level_parameter(s.axes[best.b], levels[best.b], best.level));
      where = "face '" + s.axes[best.b].name + "' level " + std::to_string(best.level + 1) +
              " of " + std::to_string(grid.levels[gb]);
    } else {
      const auto index = grid.unflatten(best.cell);
      for (std::size_t g = 0; g < grid.axes.size(); ++g) {
        const std::size_t k = grid.axes[g];
        if (k == best.a) continue;
        fixed.emplace_back(k, level_parameter(s.axes[k], levels[k], static_cast<std::size_t>(index[g])));
      }
      where = "line through " + cell_text(s, grid, best.cell);
    }
    ConstraintGroup group = derivative_constraints(s, best.a, best.order, fixed);
    group.origin = "missing-cells";
    group.description += " [" + where + "; the data hold " + std::to_string(best.order) +
                         " level(s) of '" + s.axes[best.a].name + "' there]";
    for (std::size_t cell : best.covers) {
      const auto g_index = grid.unflatten(cell);
      std::vector<int> full(s.axes.size(), -1);  // -1 for scattered axes (not part of cells)
      for (std::size_t g = 0; g < grid.axes.size(); ++g) full[grid.axes[g]] = g_index[g];
      group.cells.push_back(full);
    }
    s.constraints.push_back(std::move(group));
    std::vector<std::size_t> remaining;
    for (std::size_t cell : open)
      if (std::find(best.covers.begin(), best.covers.end(), cell) == best.covers.end())
        remaining.push_back(cell);
    open.swap(remaining);
  }
}

void lower_degree_for_missing_cells(Surface& s, const Grid& grid,
                                    const std::vector<std::size_t>& open) {
  // For each axis: the degree that the data determine on every line through an open cell.
  std::size_t best_axis = s.axes.size();
  int best_degree = 0;
  std::size_t best_size = 0;
  for (std::size_t g = 0; g < grid.axes.size(); ++g) {
    const std::size_t a = grid.axes[g];
    int m = s.axes[a].degree + 1;
    for (std::size_t cell : open) m = std::min(m, grid.occupied_on_line(cell, g));
    if (m < 1) continue;
    Surface trial = s;
    trial.axes[a].degree = m - 1;
    if (best_axis == s.axes.size() || trial.size() > best_size) {
      best_axis = a;
      best_degree = m - 1;
      best_size = trial.size();
    }
  }
  if (best_axis == s.axes.size())
    throw core::UsageError("the empty cells of the level grid, e.g. " + cell_text(s, grid, open[0]) +
                           ", cannot be handled by lowering one axis's degree; use constraints");
  ConstraintGroup group;
  group.origin = "lowered-degree";
  group.description = "degree of '" + s.axes[best_axis].name + "' lowered from " +
                      std::to_string(s.axes[best_axis].degree) + " to " +
                      std::to_string(best_degree) + " for missing cells (Report V §5.3)";
  for (std::size_t cell : open) {
    const auto g_index = grid.unflatten(cell);
    std::vector<int> full(s.axes.size(), -1);
    for (std::size_t g = 0; g < grid.axes.size(); ++g) full[grid.axes[g]] = g_index[g];
    group.cells.push_back(full);
  }
  s.axes[best_axis].degree = best_degree;
  s.constraints.push_back(std::move(group));
}

}  // namespace

std::optional<Grid> level_grid(const Surface& s, const std::vector<LevelAxis>& levels,
                               const std::vector<std::int32_t>& level_index) {
  const std::size_t n = s.axes.size();
  Grid grid;
  std::size_t cells = 1;
  for (std::size_t k = 0; k < n; ++k)
    if (!s.axes[k].scattered) {
      grid.axes.push_back(k);
      grid.levels.push_back(levels[k].centres.size());
      cells *= levels[k].centres.size();
      if (cells > kMaxGridCells) break;
    }
  if (grid.axes.empty() || cells > kMaxGridCells) return std::nullopt;
  grid.strides.assign(grid.axes.size(), 1);
  for (std::size_t g = grid.axes.size() - 1; g-- > 0;) grid.strides[g] = grid.strides[g + 1] * grid.levels[g + 1];
  grid.count.assign(cells, 0);
  for (std::size_t r = 0; r < level_index.size() / n; ++r) {
    std::size_t cell = 0;
    for (std::size_t g = 0; g < grid.axes.size(); ++g)
      cell += grid.strides[g] * static_cast<std::size_t>(level_index[r * n + grid.axes[g]]);
    ++grid.count[cell];
  }
  return grid;
}

void check_collinear(const Surface& s, const Grid& grid, const std::string& source) {
  const std::size_t G = grid.axes.size();
  for (std::size_t ga = 0; ga < G; ++ga)
    for (std::size_t gb = ga + 1; gb < G; ++gb) {
      const std::size_t La = grid.levels[ga], Lb = grid.levels[gb];
      if (La < 2 || Lb < 2) continue;
      std::vector<char> pair(La * Lb, 0);
      for (std::size_t cell = 0; cell < grid.cells(); ++cell)
        if (grid.count[cell] > 0)
          pair[((cell / grid.strides[ga]) % La) * Lb + (cell / grid.strides[gb]) % Lb] = 1;
      std::vector<int> per_a(La, 0), per_b(Lb, 0);
      for (std::size_t i = 0; i < La; ++i)
        for (std::size_t j = 0; j < Lb; ++j)
          if (pair[i * Lb + j]) ++per_a[i], ++per_b[j];
      const bool one_to_one = std::all_of(per_a.begin(), per_a.end(), [](int n) { return n == 1; }) &&
                              std::all_of(per_b.begin(), per_b.end(), [](int n) { return n == 1; });
      if (one_to_one)
        throw core::InputError("axes '" + s.axes[grid.axes[ga]].name + "' and '" +
                                   s.axes[grid.axes[gb]].name +
                                   "' are collinear in the data: each level of one occurs with "
                                   "exactly one level of the other, so their effects cannot be "
                                   "separated; fit one of them only or add data",
                               source);
    }
}

void remedy_missing_cells(Surface& s, const Grid& grid, const std::vector<LevelAxis>& levels,
                          const FitOptions& options) {
  const std::size_t cells = grid.cells();
  std::vector<std::size_t> empty;
  for (std::size_t cell = 0; cell < cells; ++cell)
    if (grid.count[cell] == 0) {
      empty.push_back(cell);
      const auto g_index = grid.unflatten(cell);
      std::vector<int> full(s.axes.size(), -1);
      for (std::size_t g = 0; g < grid.axes.size(); ++g) full[grid.axes[g]] = g_index[g];
      s.missing_cells.push_back(full);
    }
  const auto open = undetermined_cells(s, grid, empty);
  if (open.empty()) return;
  if (options.missing == MissingCellRemedy::lower_degree) {  // lowering needs no data in the cells
    lower_degree_for_missing_cells(s, grid, open);
    return;
  }
  if (open.size() > cells - empty.size())  // more undetermined than occupied cells
    throw core::UsageError(std::to_string(empty.size()) + " of " + std::to_string(cells) +
                           " cells of the level grid are empty, more than hold data; local constraints cannot "
                           "stand in for that much missing data (Report V §5.3); lower degrees (--degree or "
                           "--missing lower-degree) or supply constraints");
  if (options.missing == MissingCellRemedy::constrain) constrain_missing_cells(s, grid, levels, open);
}

}  // namespace fitlib::surface::detail
