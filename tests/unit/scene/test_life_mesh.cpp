// The life's default segment mesh (scene::life_mesh(), docs/segment.md §Mesh), both levels: graded
// towards the central gap bottom where N1 is read; a point's stress read over the elements sharing it.
#include <gtest/gtest.h>

#include <algorithm>

#include "fitlib/scene/segment_life.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/solver.hpp"

namespace fitlib::scene {

// The life mesh (scene::life_mesh()): its size, and its elements positive and bounded in shape.
// Measured: min det J / mean 0.709, aspect ratio 7.46 (the ends' 2.5 mm columns over the graded
// rows); ungraded 0.779 and 5.15.
TEST(LifeMesh, HasItsElementCountAndWellShapedElements) {
  const segment::Mesh m = segment::build_mesh(segment::CogSection{}, life_mesh());
  EXPECT_EQ(m.element_count(), 192);
  const segment::MeshQuality q = segment::mesh_quality(m);
  EXPECT_GT(q.min_jacobian_ratio, 0.6);
  EXPECT_LT(q.max_aspect_ratio, 8.0);
  // Nodes on the profile: every bottom edge's nodes lie on it (the midside too).
  for (const segment::Edge& e : m.bottom_edges)
    for (int a : e.nodes) EXPECT_NEAR(m.X[a].y(), segment::CogSection{}.bottom_y_mm(m.X[a].x()), 1e-12);
}

// A point's stress on the life mesh (docs/decisions.md "Segment: a point's stress is averaged over
// the elements that share it"): N1's gap bottom and N2's mid-cushion lie on column edges, and a
// point on the cushion/bottom interface on a corner of four elements; the reading is the mean over
// the elements of the first one's role that hold the point, an element's own interior point its own.
// Each element's integration points carry σ = e·I (e its index), so the mean is known.
TEST(LifeMesh, APointsStressIsTheMeanOverTheElementsOfItsRoleThatShareIt) {
  const segment::CogSection section;
  const segment::Mesh m = segment::build_mesh(section, life_mesh());
  segment::StaticSolution s;
  for (int e = 0; e < m.element_count(); ++e) {
    segment::IntegrationPointStress q;
    q.cauchy_MPa = static_cast<double>(e) * Eigen::Matrix2d::Identity();
    s.points.emplace_back(4, q);  // 2 × 2 points (CPE8R)
  }
  const auto mean_of = [&](const segment::PointLocation& at) {
    double sum = at.element;
    for (const segment::ElementPoint& p : at.shared) sum += p.element;
    return sum / (1.0 + static_cast<double>(at.shared.size()));
  };
  struct Case {
    Eigen::Vector2d X;
    std::size_t shared;
  };
  const Case cases[] = {{{0.0, section.land_y_mm()}, 1},      // gap bottom: two columns at the surface
                        {{0.0, -0.5 * section.cushion_mm}, 1},  // mid-cushion: one row, a column edge
                        {{0.0, -section.cushion_mm}, 1},        // the interface: two of the four elements
                        {{0.0, -0.1}, 1}};
  for (const Case& c : cases) {
    const segment::PointLocation at = segment::locate(m, c.X);
    ASSERT_EQ(at.shared.size(), c.shared) << c.X.transpose();
    for (const segment::ElementPoint& p : at.shared) EXPECT_EQ(m.roles[p.element], m.roles[at.element]);
    const segment::IntegrationPointStress q = segment::interpolate(s, at, 2, c.X);
    EXPECT_NEAR(q.cauchy_MPa(0, 0), mean_of(at), 1e-12) << c.X.transpose();
    EXPECT_NEAR(q.cauchy_MPa(0, 1), 0.0, 1e-12);
  }
  // Inside one element: its own stress.
  const segment::PointLocation inside = segment::locate(m, Eigen::Vector2d(0.2, -0.2));
  EXPECT_TRUE(inside.shared.empty());
  EXPECT_NEAR(segment::interpolate(s, inside, 2, Eigen::Vector2d(0.2, -0.2)).cauchy_MPa(1, 1), inside.element, 1e-12);
}

}  // namespace fitlib::scene
