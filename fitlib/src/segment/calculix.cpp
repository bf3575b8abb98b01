#include "fitlib/segment/calculix.hpp"

#include <cmath>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib::segment {

std::string calculix_deck(const StaticProblem& p, const std::array<IsotropicElastic, 2>& materials, int increments,
                          ElasticLaw law) {
  const Mesh& m = *p.mesh;
  if (m.nodes_per_element != 8) throw core::UsageError("calculix_deck: CPE8R needs the 8-node mesh");
  if (law == ElasticLaw::hencky) throw core::UsageError("calculix_deck: no CalculiX Hencky law");
  // 13 significant digits: at most 20 characters, CalculiX's field (docs/formats.md §3).
  const auto num = [](double x) { return core::format_number(x, 13); };
  std::ostringstream o;
  o << "** fitlib segment: plane strain, NLGEOM, CPE8R\n*NODE, NSET=NALL\n";
  for (int a = 0; a < m.node_count(); ++a) o << a + 1 << ", " << num(m.X[a].x()) << ", " << num(m.X[a].y()) << "\n";
  for (Role role : {Role::bottom, Role::cushion}) {
    o << "*ELEMENT, TYPE=CPE8R, ELSET=E" << to_string(role) << "\n";
    for (int e = 0; e < m.element_count(); ++e) {
      if (m.roles[e] != role) continue;
      o << e + 1;
      for (int a = 0; a < 8; ++a) o << ", " << m.elements[e][a] + 1;
      o << "\n";
    }
  }
  o << "*ELSET, ELSET=EALL\nEbottom, Ecushion\n";
  for (Role role : {Role::bottom, Role::cushion}) {
    const auto& mat = materials[static_cast<int>(role)];
    o << "*MATERIAL, NAME=M" << to_string(role) << "\n";
    const double mu = mat.E_MPa / (2.0 * (1.0 + mat.nu)), K = mat.E_MPa / (3.0 * (1.0 - 2.0 * mat.nu));
    if (law == ElasticLaw::neo_hookean) o << "*HYPERELASTIC, NEO HOOKE\n" << num(0.5 * mu) << ", " << num(2.0 / K) << "\n";
    else o << "*ELASTIC\n" << num(mat.E_MPa) << ", " << num(mat.nu) << "\n";
    o << "*SOLID SECTION, ELSET=E" << to_string(role) << ", MATERIAL=M" << to_string(role) << "\n1.\n";
  }
  std::vector<std::array<double, 2>> values(p.constraints.size());
  p.motion->values(1.0, values);
  for (std::size_t c = 0; c < p.constraints.size(); ++c) {
    const double a = p.constraints[c].angle_rad;
    if (a == 0.0) continue;
    o << "*NSET, NSET=T" << c << "\n" << p.constraints[c].node + 1 << "\n*TRANSFORM, NSET=T" << c << ", TYPE=R\n"
      << num(std::cos(a)) << ", " << num(std::sin(a)) << ", 0., " << num(-std::sin(a)) << ", " << num(std::cos(a))
      << ", 0.\n";
  }
  o << "*STEP, NLGEOM, INC=1000\n*STATIC\n" << num(1.0 / increments) << ", 1.\n*BOUNDARY\n";
  for (std::size_t c = 0; c < p.constraints.size(); ++c)
    for (int k = 0; k < 2; ++k)
      if (p.constraints[c].fixed[k]) o << p.constraints[c].node + 1 << ", " << k + 1 << ", " << k + 1 << ", " << num(values[c][k]) << "\n";
  for (const LoadPtr& load : p.loads) {  // the static cases' one load (the deck knows no other)
    const auto* pressure = dynamic_cast<const FollowerPressure*>(load.get());
    if (!pressure) throw core::UsageError("calculix_deck: only the follower pressure is written");
    if (pressure->pressure_MPa() == 0.0) continue;
    o << "*DLOAD\n";
    for (const Edge& e : m.bottom_edges) o << e.element + 1 << ", P1, " << num(pressure->pressure_MPa()) << "\n";
  }
  o << "*EL PRINT, ELSET=EALL\nS\n*END STEP\n";
  return o.str();
}

StaticSolution read_calculix_stresses(const std::string& text, const Mesh& m) {
  StaticSolution s;
  s.points.assign(m.element_count(), {});
  std::istringstream in(text);
  std::string line;
  bool in_block = false;
  while (std::getline(in, line)) {
    if (line.find("stresses") != std::string::npos) {
      in_block = true;
      for (auto& v : s.points) v.clear();  // keep the last time only
      continue;
    }
    if (!in_block) continue;
    std::istringstream l(line);
    int e = 0, ip = 0;
    double sxx, syy, szz, sxy, sxz, syz;
    if (!(l >> e >> ip >> sxx >> syy >> szz >> sxy >> sxz >> syz)) continue;
    if (e < 1 || e > m.element_count() || ip > 4) continue;  // 3-D expansion: the first layer
    IntegrationPointStress g;
    g.cauchy_MPa << sxx, sxy, sxy, syy;
    g.sigma33_MPa = szz;
    s.points[e - 1].push_back(g);
  }
  for (const auto& v : s.points)
    if (v.size() != 4) throw core::InputError("CalculiX .dat: expected 4 integration points for every element");
  return s;
}

}  // namespace fitlib::segment
