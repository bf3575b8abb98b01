#include "fitlib/segment/mesh.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "element.hpp"

namespace fitlib::segment {

namespace {

// Column boundaries: coarse | fine (even count, so a column line falls on the gap centre x = 0) | coarse.
std::vector<double> uniform_column_lines(const CogSection& s, const MeshKnobs& k) {
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

// Lines a = x_0 < … < x_n = b at equal steps of ∫ dx / width(x) (midpoint rule on 2048 slices),
// n the least count whose columns are no wider than width(x); x_n is left out.
std::vector<double> graded_lines(double a, double b, const std::function<double(double)>& width) {
  constexpr int kSlices = 2048;
  std::vector<double> phi(kSlices + 1, 0.0);
  const double dx = (b - a) / kSlices;
  for (int i = 0; i < kSlices; ++i) phi[i + 1] = phi[i] + dx / width(a + (i + 0.5) * dx);
  const int n = std::max(1, static_cast<int>(std::ceil(phi.back() - 1e-9)));
  std::vector<double> x{a};
  for (int j = 1, i = 0; j < n; ++j) {
    const double target = phi.back() * j / n;
    while (phi[i + 1] < target) ++i;
    x.push_back(a + dx * (i + (target - phi[i]) / (phi[i + 1] - phi[i])));
  }
  return x;
}

// Graded columns (MeshKnobs::gap_size_mm > 0): each half built from the centre outwards and
// mirrored, so x = 0 is a line and the mesh is symmetric.
std::vector<double> graded_column_lines(const CogSection& s, const MeshKnobs& k) {
  const double half = 0.5 * k.central_pitches * s.cog_pitch_mm, end = k.end_pitches * s.cog_pitch_mm;
  std::vector<double> gaps;  // gap centres in the central section, x ≥ 0
  for (double g = 0.0; g <= half + 1e-9; g += s.cog_pitch_mm) gaps.push_back(g);
  const auto width = [&](double base) {
    return [&, base](double x) {
      double d = std::abs(x - gaps.front());
      for (double g : gaps) d = std::min(d, std::abs(x - g));
      return std::min(base, k.gap_size_mm + k.column_growth * d);
    };
  };
  std::vector<double> right = graded_lines(0.0, half, width(k.fine_size_mm));
  if (end > 0.0)
    for (double x : graded_lines(half, half + end, width(k.coarse_size_mm))) right.push_back(x);
  right.push_back(half + end);
  std::vector<double> x;
  for (auto it = right.rbegin(); it != right.rend(); ++it) x.push_back(-*it);
  x.insert(x.end(), right.begin() + 1, right.end());
  return x;
}

std::vector<double> column_lines(const CogSection& s, const MeshKnobs& k) {
  return k.gap_size_mm > 0.0 ? graded_column_lines(s, k) : uniform_column_lines(s, k);
}

// Depth of half-row J (0 … 2n) of the bottom rubber as a fraction of its height from the cushion
// interface: rows growing by `growth` upwards from the profile; the midside half-rows halfway.
double bottom_row_fraction(int J, int n, double growth) {
  if (J % 2 == 1) return 0.5 * (bottom_row_fraction(J - 1, n, growth) + bottom_row_fraction(J + 1, n, growth));
  const int above_profile = n - J / 2;
  return 1.0 - (std::pow(growth, above_profile) - 1.0) / (std::pow(growth, n) - 1.0);
}

}  // namespace

double reference_jacobian(const Mesh& m, int e, double xi, double eta) {
  double N[8], dN_dxi[8], dN_deta[8];
  detail::shape(m.nodes_per_element, xi, eta, N, dN_dxi, dN_deta);
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (int a = 0; a < m.nodes_per_element; ++a) {
    J.col(0) += dN_dxi[a] * m.X[m.elements[e][a]];
    J.col(1) += dN_deta[a] * m.X[m.elements[e][a]];
  }
  return J.determinant();
}

Mesh build_mesh(const CogSection& s, const MeshKnobs& k) {
  s.validate();
  if (k.nodes_per_element != 4 && k.nodes_per_element != 8)
    throw core::UsageError("mesh: nodes_per_element must be 4 or 8");
  if (!(k.fine_size_mm > 0.0) || !(k.coarse_size_mm > 0.0) || k.cushion_rows < 1 ||
      !(k.central_pitches > 0.0) || !(k.end_pitches >= 0.0))
    throw core::UsageError("mesh: element sizes and section lengths must be positive");
  if (!(k.gap_size_mm >= 0.0) || !(k.column_growth > 0.0) || !(k.row_growth > 0.0))
    throw core::UsageError("mesh: gap_size_mm must be ≥ 0, column_growth and row_growth positive");
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
      const int Jb = J - 2 * rows_c;  // half-row in the bottom rubber
      const double y = Jb <= 0 ? -s.cushion_mm * J / (2.0 * rows_c)
                               : -s.cushion_mm + (yb + s.cushion_mm) * (k.row_growth == 1.0
                                                                             ? Jb / (2.0 * rows_b)
                                                                             : bottom_row_fraction(Jb, rows_b, k.row_growth));
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

MeshQuality mesh_quality(const Mesh& m) {
  MeshQuality q;
  q.min_jacobian_ratio = std::numeric_limits<double>::infinity();
  q.shortest_side_mm = std::numeric_limits<double>::infinity();
  for (int e = 0; e < m.element_count(); ++e) {
    double area = 0.0, worst = std::numeric_limits<double>::infinity();
    for (const detail::GaussPoint& g : detail::gauss_rule(3)) area += g.weight * reference_jacobian(m, e, g.xi, g.eta);
    for (double xi : {-1.0, 0.0, 1.0})
      for (double eta : {-1.0, 0.0, 1.0}) worst = std::min(worst, reference_jacobian(m, e, xi, eta) / (0.25 * std::abs(area)));
    if (worst < q.min_jacobian_ratio) q.min_jacobian_ratio = worst, q.worst_jacobian_element = e;
    double longest = 0.0, shortest = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 4; ++a) {
      const double side = (m.X[m.elements[e][(a + 1) % 4]] - m.X[m.elements[e][a]]).norm();
      longest = std::max(longest, side), shortest = std::min(shortest, side);
    }
    q.shortest_side_mm = std::min(q.shortest_side_mm, shortest);
    if (longest / shortest > q.max_aspect_ratio) q.max_aspect_ratio = longest / shortest, q.worst_aspect_element = e;
  }
  return q;
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
