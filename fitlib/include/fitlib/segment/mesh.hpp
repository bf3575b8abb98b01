#pragma once
// Structured quadrilateral mesh of the segment's longitudinal section (CogSection): vertical
// element columns, a fine central section and coarse leading/trailing sections, rows mapped
// linearly between the cord line, the cushion interface and the cogged bottom profile.
// Elements are 8-node serendipity quads (CalculiX CPE8 / VTK 23 node order) or 4-node quads.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fitlib/segment/section.hpp"

namespace fitlib::segment {

enum class Role { bottom = 0, cushion = 1 };
const char* to_string(Role role);

struct MeshKnobs {
  double central_pitches = 2.0;   // fine central section length, in cog pitches
  double end_pitches = 2.0;       // coarse leading and trailing sections, each
  double fine_size_mm = 0.4;      // element width in the central section, and row height
  double coarse_size_mm = 1.5;    // element width in the leading/trailing sections
  int cushion_rows = 2;
  int nodes_per_element = 8;      // 8 (quadratic) or 4 (bilinear)
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

// Legacy VTK unstructured grid (ParaView): roles as cell data; optional point vectors and cell
// tensors (name → per-point (ux, uy) or per-cell (σ11, σ22, σ12, σ33)).
struct VtkFields {
  std::vector<Eigen::Vector2d> displacement_mm;           // per node, may be empty
  std::vector<std::array<double, 4>> cell_stress_MPa;     // per element, may be empty
};
void write_vtk(const Mesh& mesh, const std::string& path, const VtkFields& fields = {});

}  // namespace fitlib::segment
