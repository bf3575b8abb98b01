#include "fitlib/segment/mesh.hpp"

#include <cmath>
#include <map>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"

namespace fitlib::segment {

const char* to_string(Role role) { return role == Role::bottom ? "bottom" : "cushion"; }

namespace {

// Column boundaries: coarse | fine (even count, so a column line falls on the gap centre x = 0) | coarse.
std::vector<double> column_lines(const CogSection& s, const MeshKnobs& k) {
  const double fine = k.central_pitches * s.cog_pitch_mm, end = k.end_pitches * s.cog_pitch_mm;
  int nf = static_cast<int>(std::ceil(fine / k.fine_size_mm - 1e-9));
  nf += nf % 2;
  const int ne = end > 0.0 ? std::max(1, static_cast<int>(std::ceil(end / k.coarse_size_mm - 1e-9))) : 0;
  std::vector<double> x;
  const double x0 = -0.5 * fine - end;
  for (int i = 0; i < ne; ++i) x.push_back(x0 + end * i / ne);
  for (int i = 0; i < nf; ++i) x.push_back(-0.5 * fine + fine * i / nf);
  for (int i = 0; i <= ne; ++i) x.push_back(0.5 * fine + (ne > 0 ? end * i / ne : 0.0));
  return x;
}

}  // namespace

Mesh build_mesh(const CogSection& s, const MeshKnobs& k) {
  s.validate();
  if (k.nodes_per_element != 4 && k.nodes_per_element != 8)
    throw core::UsageError("mesh: nodes_per_element must be 4 or 8");
  if (!(k.fine_size_mm > 0.0) || !(k.coarse_size_mm > 0.0) || k.cushion_rows < 1 ||
      !(k.central_pitches > 0.0) || !(k.end_pitches >= 0.0))
    throw core::UsageError("mesh: element sizes and section lengths must be positive");
  const bool quad8 = k.nodes_per_element == 8;
  const std::vector<double> xl = column_lines(s, k);
  const int nc = static_cast<int>(xl.size()) - 1;
  const int rows_c = k.cushion_rows;
  const int rows_b = std::max(2, static_cast<int>(std::ceil((s.height_mm - s.cushion_mm) / k.fine_size_mm - 1e-9)));
  const int nr = rows_c + rows_b;

  Mesh m;
  m.nodes_per_element = k.nodes_per_element;
  m.half_length_mm = 0.5 * (xl.back() - xl.front());
  // Node grid on half steps; (I odd, J odd) is an element centre and has no node.
  const int NI = 2 * nc + 1, NJ = 2 * nr + 1;
  std::vector<int> id(static_cast<std::size_t>(NI) * NJ, -1);
  auto at = [&](int I, int J) -> int& { return id[static_cast<std::size_t>(I) * NJ + J]; };
  for (int I = 0; I < NI; ++I) {
    const double x = (I % 2 == 0) ? xl[I / 2] : 0.5 * (xl[I / 2] + xl[I / 2 + 1]);
    const double yb = s.bottom_y_mm(x);
    for (int J = 0; J < NJ; ++J) {  // J = 0 on the cord line, NJ − 1 on the bottom
      const bool centre = (I % 2 == 1) && (J % 2 == 1);
      const bool needed = quad8 ? !centre : (I % 2 == 0 && J % 2 == 0);
      if (!needed) continue;
      const double y = (J <= 2 * rows_c) ? -s.cushion_mm * J / (2.0 * rows_c)
                                         : -s.cushion_mm + (yb + s.cushion_mm) * (J - 2 * rows_c) / (2.0 * rows_b);
      at(I, J) = static_cast<int>(m.X.size());
      m.X.emplace_back(x, y);
    }
  }
  for (int c = 0; c < nc; ++c)
    for (int r = 0; r < nr; ++r) {
      const int I = 2 * c, J = 2 * r;  // upper-left corner; J + 2 is the lower row
      std::array<int, 8> e{at(I, J + 2), at(I + 2, J + 2), at(I + 2, J), at(I, J), -1, -1, -1, -1};
      if (quad8) e = {e[0], e[1], e[2], e[3], at(I + 1, J + 2), at(I + 2, J + 1), at(I + 1, J), at(I, J + 1)};
      m.elements.push_back(e);
      m.roles.push_back(r < rows_c ? Role::cushion : Role::bottom);
      if (r == nr - 1) m.bottom_edges.push_back({m.element_count() - 1, {e[0], e[1], quad8 ? e[4] : -1}});
    }
  for (int I = 0; I < NI; ++I)
    if (at(I, 0) >= 0) m.top_nodes.push_back(at(I, 0));
  for (int J = 0; J < NJ; ++J) {
    if (at(0, J) >= 0) m.left_nodes.push_back(at(0, J));
    if (at(NI - 1, J) >= 0) m.right_nodes.push_back(at(NI - 1, J));
  }
  return m;
}

void write_vtk(const Mesh& m, const std::string& path, const VtkFields& f) {
  // Shortest round trip, locale-independent (docs/decisions.md); a NaN/inf is a NumericalError
  // naming the field and the node or cell, before anything is written.
  const auto format_number = [&](double value, const std::string& field, std::size_t index) {
    if (!std::isfinite(value))
      throw core::NumericalError(path + ": " + field + " " + std::to_string(index + 1) + " is not finite");
    return core::format_number(value);
  };
  std::ostringstream o;
  o << "# vtk DataFile Version 3.0\nfitlib segment mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  o << "POINTS " << m.node_count() << " double\n";
  for (std::size_t i = 0; i < m.X.size(); ++i)
    o << format_number(m.X[i].x(), "x of node", i) << " " << format_number(m.X[i].y(), "y of node", i) << " 0\n";
  const int npe = m.nodes_per_element;
  o << "CELLS " << m.element_count() << " " << m.element_count() * (npe + 1) << "\n";
  for (const auto& e : m.elements) {
    o << npe;
    for (int a = 0; a < npe; ++a) o << " " << e[a];
    o << "\n";
  }
  o << "CELL_TYPES " << m.element_count() << "\n";
  for (int i = 0; i < m.element_count(); ++i) o << (npe == 8 ? 23 : 9) << "\n";
  o << "CELL_DATA " << m.element_count() << "\nSCALARS role int 1\nLOOKUP_TABLE default\n";
  for (Role r : m.roles) o << static_cast<int>(r) << "\n";
  if (!f.cell_stress_MPa.empty()) {
    const char* names[4] = {"sigma_xx_MPa", "sigma_yy_MPa", "sigma_xy_MPa", "sigma_zz_MPa"};
    for (int c = 0; c < 4; ++c) {
      o << "SCALARS " << names[c] << " double 1\nLOOKUP_TABLE default\n";
      for (std::size_t i = 0; i < f.cell_stress_MPa.size(); ++i)
        o << format_number(f.cell_stress_MPa[i][c], std::string(names[c]) + " of cell", i) << "\n";
    }
  }
  if (!f.displacement_mm.empty()) {
    o << "POINT_DATA " << m.node_count() << "\nVECTORS displacement_mm double\n";
    for (std::size_t i = 0; i < f.displacement_mm.size(); ++i) {
      const auto& u = f.displacement_mm[i];
      o << format_number(u.x(), "x displacement of node", i) << " " << format_number(u.y(), "y displacement of node", i)
        << " 0\n";
    }
  }
  core::write_file_atomically(path, o.str());
}

}  // namespace fitlib::segment
