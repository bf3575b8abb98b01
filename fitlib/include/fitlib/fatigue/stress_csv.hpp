#pragma once
// Stress histories at monitored points as CSV, so that any FE code's results can feed the life
// evaluation (docs/fatigue.md §3). One row per point and instant:
//   point, role (bottom | cushion), x_mm, y_mm, t_s, s11_MPa, s22_MPa, s12_MPa[, e11, e22, e12]
// (1 radial, 2 longitudinal; the logarithmic strains optional, each field empty where unknown).
// Rows of a point may be interleaved with other points'; its times must increase and its role
// and position must not change.
#include <string>
#include <vector>

#include "fitlib/fatigue/life.hpp"

namespace fitlib::fatigue {

// InputError naming file, line and column for unknown or missing columns, a wrong role, a
// non-finite number, decreasing times or a point that changes role or position.
std::vector<PointHistory> parse_stress_histories(const std::string& text, const std::string& source);
std::vector<PointHistory> read_stress_histories(const std::string& path);

// The CSV of `points` (exact numbers: reads back equal).
std::string stress_histories_csv(const std::vector<PointHistory>& points);

}  // namespace fitlib::fatigue
