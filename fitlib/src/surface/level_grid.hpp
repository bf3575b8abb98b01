#pragma once
// Private: the level grid of a surface fit's data, its empty cells and their remedy (Report V
// §5.3; docs/surface.md, "Missing cells and constraints").
#include <optional>
#include <string>
#include <vector>

#include "fitlib/surface/fit.hpp"

namespace fitlib::surface::detail {

// The level grid over the non-scattered axes: occupancy of every cell.
struct Grid {
  std::vector<std::size_t> axes;     // surface axes that have levels
  std::vector<std::size_t> levels;   // number of levels per grid axis
  std::vector<std::size_t> strides;  // row-major
  std::vector<std::uint32_t> count;  // points per cell

  std::size_t cells() const { return count.size(); }
  std::vector<int> unflatten(std::size_t cell) const {
    std::vector<int> index(axes.size());
    for (std::size_t g = 0; g < axes.size(); ++g)
      index[g] = static_cast<int>((cell / strides[g]) % levels[g]);
    return index;
  }
  // Occupied levels on the line through `cell` along grid axis g.
  int occupied_on_line(std::size_t cell, std::size_t g) const {
    const std::size_t base = cell - ((cell / strides[g]) % levels[g]) * strides[g];
    int n = 0;
    for (std::size_t l = 0; l < levels[g]; ++l) n += count[base + l * strides[g]] > 0;
    return n;
  }
};

// The level grid over the axes that have levels (none when it would exceed a million cells), with
// the count of rows in every cell; level_index holds each row's level per axis (n per row).
std::optional<Grid> level_grid(const Surface& s, const std::vector<LevelAxis>& levels,
                               const std::vector<std::int32_t>& level_index);

// InputError when two grid axes are collinear in the data (each level of one occurs with exactly
// one level of the other).
void check_collinear(const Surface& s, const Grid& grid, const std::string& source);

// Records the grid's empty cells in s.missing_cells and applies the remedy of `options` to the
// undetermined ones; UsageError when more cells are undetermined than occupied.
void remedy_missing_cells(Surface& s, const Grid& grid, const std::vector<LevelAxis>& levels,
                          const FitOptions& options);

}  // namespace fitlib::surface::detail
