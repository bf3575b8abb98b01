// The life's default segment mesh (fatigue::life_mesh(), docs/segment.md §Mesh): graded towards the
// central gap bottom where N1 is read.
#include <gtest/gtest.h>

#include "fitlib/fatigue/segment_life.hpp"
#include "fitlib/segment/mesh.hpp"

namespace fitlib::fatigue {

// The life mesh (fatigue::life_mesh()): its size, and its elements positive and bounded in shape.
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

}  // namespace fitlib::fatigue
