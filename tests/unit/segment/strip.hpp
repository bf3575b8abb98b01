#pragma once
// A rectangular strip 4 mm deep (no cogs) held at its cord line, for the segment tests that need a
// closed form (the inertia's shear vibration, the flank foundation's Winkler-supported bar).
#include <array>
#include <vector>

#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/solver.hpp"

namespace fitlib::segment::test {

constexpr double kStripHeight_mm = 4.0;

// Cord line y = 0 on top, bottom at y = −4 mm, 0.5 mm elements in the middle, 1 mm at the ends.
inline Mesh strip(int nodes_per_element = 8) {
  CogSection s;
  s.height_mm = kStripHeight_mm, s.cushion_mm = 0.5, s.cog_depth_mm = 0.0, s.root_fillet_mm = s.tip_radius_mm = 0.0;
  s.cog_pitch_mm = 4.0;
  MeshKnobs k;
  k.central_pitches = 1.0, k.end_pitches = 0.5, k.fine_size_mm = 0.5, k.coarse_size_mm = 1.0, k.cushion_rows = 1;
  k.nodes_per_element = nodes_per_element;
  return build_mesh(s, k);
}

// The strip with one law, its cord line held and its end faces' global components `end_held`
// (x, y) held, all at zero displacement.
inline StaticProblem held_strip(const Mesh& m, const PlaneStrainLaw& law, std::array<bool, 2> end_held) {
  StaticProblem p;
  p.mesh = &m;
  p.laws = {&law, &law};
  for (int n : m.top_nodes) p.constraints.push_back({n, 0.0, {true, true}});
  for (const auto* side : {&m.left_nodes, &m.right_nodes})
    for (int n : *side)
      if (n != m.top_nodes.front() && n != m.top_nodes.back()) p.constraints.push_back({n, 0.0, end_held});
  p.motion = prescribed([](double, std::vector<std::array<double, 2>>& v) {
    for (auto& x : v) x = {0.0, 0.0};
  });
  return p;
}

}  // namespace fitlib::segment::test
