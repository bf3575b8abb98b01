// The segment solver's unknowns and the tangent's sparsity (dofs.hpp).
#include "dofs.hpp"

#include <algorithm>
#include <cmath>

#include "grouped_ldlt.hpp"

namespace fitlib::segment::detail {

Dofs number_dofs(const StaticProblem& p) {
  const int n = p.mesh->node_count();
  Dofs d{std::vector<Eigen::Matrix2d>(n, Eigen::Matrix2d::Identity()), std::vector<int>(2 * n, 0),
         std::vector<int>(n, -1), 0};
  for (std::size_t c = 0; c < p.constraints.size(); ++c) {
    const NodeConstraint& nc = p.constraints[c];
    const double ca = std::cos(nc.angle_rad), sa = std::sin(nc.angle_rad);
    d.R[nc.node] << ca, -sa, sa, ca;
    d.constraint[nc.node] = static_cast<int>(c);
    for (int k = 0; k < 2; ++k)
      if (nc.fixed[k]) d.eq[2 * nc.node + k] = -1;
  }
  for (int& e : d.eq)
    if (e == 0) e = d.equations++;
  return d;
}

StateBlock initial_states(const StaticProblem& p, std::size_t points_per_element) {
  const Mesh& m = *p.mesh;
  StateBlock b;
  for (int e = 0; e < m.element_count(); ++e) {
    const PlaneStrainLaw& law = p.law_of(e);
    b.offset.push_back(b.committed.size());
    const std::vector<double> virgin = law.initial_state();
    for (std::size_t q = 0; q < points_per_element; ++q) b.committed.insert(b.committed.end(), virgin.begin(), virgin.end());
  }
  b.trial = b.committed;
  return b;
}

namespace {

std::vector<int> local_dofs(const std::vector<int>& nodes, const Dofs& d) {
  std::vector<int> eq;
  for (int n : nodes)
    for (int i = 0; i < 2; ++i) eq.push_back(d.eq[2 * n + i]);
  return eq;
}

}  // namespace

std::vector<int> edge_nodes(const Edge& edge) {
  std::vector<int> n;
  for (int a : edge.nodes)
    if (a >= 0) n.push_back(a);
  return n;
}

Pattern build_pattern(const Mesh& m, const Dofs& d) {
  std::vector<std::vector<int>> blocks;
  for (const auto& el : m.elements) blocks.push_back(local_dofs({el.begin(), el.begin() + m.nodes_per_element}, d));
  for (const Edge& edge : m.bottom_edges) blocks.push_back(local_dofs(edge_nodes(edge), d));
  std::vector<Eigen::Triplet<double>> t;
  for (const auto& eq : blocks)
    for (int r : eq)
      for (int c : eq)
        if (r >= 0 && c >= 0) t.emplace_back(r, c, 0.0);
  Pattern p;
  p.K.resize(d.equations, d.equations);
  p.K.setFromTriplets(t.begin(), t.end());
  p.K.makeCompressed();
  const int* outer = p.K.outerIndexPtr();
  const int* inner = p.K.innerIndexPtr();
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const auto& eq = blocks[b];
    std::vector<int> slots(eq.size() * eq.size(), -1);
    for (std::size_t i = 0; i < eq.size(); ++i)
      for (std::size_t j = 0; j < eq.size(); ++j)
        if (eq[i] >= 0 && eq[j] >= 0)
          slots[i * eq.size() + j] = static_cast<int>(std::lower_bound(inner + outer[eq[j]], inner + outer[eq[j] + 1], eq[i]) - inner);
    (b < m.elements.size() ? p.element_slots : p.edge_slots).push_back(std::move(slots));
  }
  return p;
}

std::vector<int> diagonal_slots(const SparseMatrix& K) {
  std::vector<int> slots;
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  for (int j = 0; j < K.cols(); ++j)
    slots.push_back(static_cast<int>(std::lower_bound(inner + outer[j], inner + outer[j + 1], j) - inner));
  return slots;
}

Pattern ordered_pattern(const Mesh& m, Dofs& d) {
  const std::vector<int> order = detail::grouped_amd_order(build_pattern(m, d).K);
  std::vector<int> position(order.size());
  for (std::size_t p = 0; p < order.size(); ++p) position[order[p]] = static_cast<int>(p);
  for (int& e : d.eq)
    if (e >= 0) e = position[e];
  return build_pattern(m, d);
}

double free_norm(const Eigen::VectorXd& r, const Dofs& d, bool free) {
  double s = 0.0;
  for (int i = 0; i < r.size(); ++i)
    if ((d.eq[i] >= 0) == free) s += r(i) * r(i);
  return std::sqrt(s);
}

}  // namespace fitlib::segment::detail
