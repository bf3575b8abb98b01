// The segment mesh's grading (docs/segment.md §Mesh): columns narrowing towards the central
// section's gap centres and bottom-rubber rows thinning towards the profile, checked against the
// knobs' definitions; the quality check itself (the life mesh's shape: tests/unit/fatigue).
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "fitlib/segment/mesh.hpp"

using namespace fitlib::segment;

namespace {

// Distinct x of the corner nodes on the cord line, ascending: the column lines.
std::vector<double> column_lines(const Mesh& m) {
  std::set<double> x;
  for (const auto& e : m.elements)
    for (int a = 0; a < 4; ++a)
      if (m.X[e[a]].y() == 0.0) x.insert(m.X[e[a]].x());
  return {x.begin(), x.end()};
}

// y of the corner nodes at x, top to bottom (the row lines of that column line).
std::vector<double> row_lines_at(const Mesh& m, double x) {
  std::set<double> y;
  for (const auto& e : m.elements)
    for (int a = 0; a < 4; ++a)
      if (m.X[e[a]].x() == x) y.insert(m.X[e[a]].y());
  return {y.rbegin(), y.rend()};
}

// The life mesh's knobs (scene::life_mesh(), a module to the right of segment's tests).
MeshKnobs graded() {
  MeshKnobs k;
  k.central_pitches = 1.0, k.end_pitches = 1.0, k.fine_size_mm = 1.0, k.coarse_size_mm = 2.5, k.cushion_rows = 1;
  k.gap_size_mm = 0.3, k.column_growth = 0.25, k.row_growth = 1.1;
  return k;
}

}  // namespace

// Without the grading knobs the mesh is today's uniform one: equal columns per section, equal rows.
TEST(SegmentMesh, WithoutGradingColumnsAndRowsAreUniform) {
  MeshKnobs k;
  k.central_pitches = 1.0, k.end_pitches = 1.0, k.fine_size_mm = 1.0, k.coarse_size_mm = 2.5, k.cushion_rows = 1;
  const CogSection s;
  const Mesh m = build_mesh(s, k);
  EXPECT_EQ(m.element_count(), 144);  // (4 + 10 + 4) columns × (1 + 7) rows
  const std::vector<double> x = column_lines(m);
  ASSERT_EQ(x.size(), 19u);
  for (std::size_t i = 0; i + 1 < x.size(); ++i)
    EXPECT_NEAR(x[i + 1] - x[i], (i < 4 || i >= 14) ? 2.25 : 0.9, 1e-12) << i;
  const std::vector<double> y = row_lines_at(m, 0.0);
  ASSERT_EQ(y.size(), 9u);
  for (std::size_t j = 1; j + 1 < y.size(); ++j) EXPECT_NEAR(y[j] - y[j + 1], 3.6 / 7.0, 1e-12) << j;
}

// gap_size_mm: the columns at the gap centre x = 0 are about that wide (their width follows the
// wanted width over them, gap + growth · distance), widths follow min(size, gap + growth · distance)
// to within one column's rounding, neighbours differ by about 1 + growth (more where the central
// section meets an end: each section's count is rounded up on its own), the mesh is
// mirror-symmetric with a line on x = 0 (the section force's cut).
TEST(SegmentMesh, GradedColumnsNarrowTowardsTheGapCentreAndGrowByTheKnob) {
  const MeshKnobs k = graded();
  const CogSection s;
  const std::vector<double> x = column_lines(build_mesh(s, k));
  const std::size_t n = x.size();
  ASSERT_EQ(n % 2, 1u);
  EXPECT_EQ(x[n / 2], 0.0);
  for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(x[i], -x[n - 1 - i], 1e-12) << i;
  const double w0 = x[n / 2 + 1];
  EXPECT_LE(w0, k.gap_size_mm + k.column_growth * w0);
  EXPECT_GT(w0, k.gap_size_mm);
  for (std::size_t i = n / 2; i + 1 < n; ++i) {
    const double w = x[i + 1] - x[i], mid = 0.5 * (x[i + 1] + x[i]);
    const double wanted = std::min(mid <= 4.5 ? k.fine_size_mm : k.coarse_size_mm,
                                   k.gap_size_mm + k.column_growth * mid);
    EXPECT_LE(w, 1.25 * wanted) << "column at " << mid;
    EXPECT_GE(w, 0.7 * wanted) << "column at " << mid;
    const bool section_start = std::abs(x[i] - 4.5) < 1e-12;
    if (i > n / 2) {
      EXPECT_LE(w / (x[i] - x[i - 1]), section_start ? 1.5 : 1.0 + 1.3 * k.column_growth) << mid;
    }
  }
}

// row_growth: in every column each bottom-rubber row is row_growth × the one below it, and the rows
// fill the bottom rubber; the cushion rows stay equal.
TEST(SegmentMesh, GradedRowsGrowGeometricallyFromTheProfile) {
  const MeshKnobs k = graded();
  const CogSection s;
  const Mesh m = build_mesh(s, k);
  for (double x : {0.0, 4.5, 13.5}) {
    const std::vector<double> y = row_lines_at(m, x);
    ASSERT_EQ(y.size(), 9u);
    EXPECT_NEAR(y[1], -s.cushion_mm, 1e-12);
    EXPECT_NEAR(y.back(), s.bottom_y_mm(x), 1e-12);
    for (std::size_t j = 1; j + 2 < y.size(); ++j)
      EXPECT_NEAR((y[j] - y[j + 1]) / (y[j + 1] - y[j + 2]), k.row_growth, 1e-9) << "x " << x << " row " << j;
  }
}

// The check sees a folded element (a corner pulled across the opposite side), an inverted
// (clockwise) one and a long one.
TEST(SegmentMesh, QualityCheckFindsAFoldedAndAStretchedElement) {
  Mesh m;
  m.nodes_per_element = 4;
  m.X = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {5, 0}, {5, 1}};
  m.elements = {{0, 1, 2, 3, -1, -1, -1, -1}, {1, 4, 5, 2, -1, -1, -1, -1}};
  MeshQuality q = mesh_quality(m);
  EXPECT_NEAR(q.min_jacobian_ratio, 1.0, 1e-12);
  EXPECT_NEAR(q.max_aspect_ratio, 4.0, 1e-12);
  EXPECT_EQ(q.worst_aspect_element, 1);
  m.X[2] = {-0.5, -0.5};  // element 0's third corner across its first side: folded
  q = mesh_quality(m);
  EXPECT_LE(q.min_jacobian_ratio, 0.0);
  EXPECT_EQ(q.worst_jacobian_element, 0);
  m.X[2] = {1, 1};
  m.elements[1] = {1, 2, 5, 4, -1, -1, -1, -1};  // clockwise: wholly inverted
  q = mesh_quality(m);
  EXPECT_NEAR(q.min_jacobian_ratio, -1.0, 1e-12);
  EXPECT_EQ(q.worst_jacobian_element, 1);
}
