#pragma once
// Structured quadrilateral mesh of the segment's longitudinal section (CogSection): vertical
// element columns, a fine central section and coarse leading/trailing sections, rows mapped
// between the cord line, the cushion interface and the cogged bottom profile. Optional grading
// (docs/segment.md §Mesh): narrower columns around the central section's gap centres and
// bottom-rubber rows thinning towards the profile, where the gap bottom's stress gradient is.
// Elements are 8-node serendipity quads (CalculiX CPE8 / VTK 23 node order) or 4-node quads.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fitlib/core/material_role.hpp"
#include "fitlib/segment/section.hpp"

namespace fitlib::segment {

using Role = core::MaterialRole;  // an element's rubber: bottom (0) or cushion (1); core::to_string

struct MeshKnobs {
  double central_pitches = 2.0;   // fine central section length, in cog pitches
  double end_pitches = 2.0;       // coarse leading and trailing sections, each
  double fine_size_mm = 0.4;      // element width in the central section, and row height
  double coarse_size_mm = 1.5;    // element width in the leading/trailing sections
  int cushion_rows = 2;
  int nodes_per_element = 8;      // 8 (quadratic) or 4 (bilinear)
  // Grading (0 and 1: none, today's uniform mesh). Column width at distance d from the nearest gap
  // centre of the central section: min(section size, gap_size_mm + column_growth · d).
  double gap_size_mm = 0.0;
  double column_growth = 0.25;    // width added per mm from the gap centre (≈ neighbour ratio − 1)
  double row_growth = 1.0;        // each bottom-rubber row this × the one below it (towards the cord)
};

struct Edge {  // an element side on the bottom boundary: element, local corners a → b (+ midside)
  int element;
  std::array<int, 3> nodes;  // a, b, midside (−1 for 4-node elements)
};

struct Mesh {
  int nodes_per_element = 8;
  std::vector<Eigen::Vector2d> X;                // reference node positions, mm
  std::vector<std::array<int, 8>> elements;      // corners counter-clockwise, then midsides
  std::vector<Role> roles;
  std::vector<int> top_nodes;                    // the cord line, left to right
  std::vector<int> left_nodes, right_nodes;      // end faces, top to bottom
  std::vector<Edge> bottom_edges;                // left to right
  double half_length_mm = 0.0;

  int node_count() const { return static_cast<int>(X.size()); }
  int element_count() const { return static_cast<int>(elements.size()); }
};

Mesh build_mesh(const CogSection& section, const MeshKnobs& knobs);

// det(∂X/∂ξ) of element e's reference map at (ξ, η) ∈ [−1, 1]².
double reference_jacobian(const Mesh& mesh, int element, double xi, double eta);

// Shape of the mesh's elements: det(∂X/∂ξ) at the 3 × 3 points ξ, η ∈ {−1, 0, 1} against the
// element's mean magnitude (|area| / 4; ≤ 0: inverted or folded), and the longest corner-to-corner side over
// the shortest.
struct MeshQuality {
  double min_jacobian_ratio = 0.0;
  int worst_jacobian_element = -1;
  double max_aspect_ratio = 0.0;
  int worst_aspect_element = -1;
  double shortest_side_mm = 0.0;  // the shortest corner-to-corner side of any element
};
MeshQuality mesh_quality(const Mesh& mesh);

// Legacy VTK unstructured grid (ParaView): roles as cell data; optional point vectors and cell
// tensors (name → per-point (ux, uy) or per-cell (σ11, σ22, σ12, σ33)).
struct VtkFields {
  std::vector<Eigen::Vector2d> displacement_mm;           // per node, may be empty
  std::vector<std::array<double, 4>> cell_stress_MPa;     // per element, may be empty
};
void write_vtk(const Mesh& mesh, const std::string& path, const VtkFields& fields = {});

}  // namespace fitlib::segment
