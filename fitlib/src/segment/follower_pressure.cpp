// The follower pressure on the bottom edges (fitlib/segment/load.hpp): λ p normal to the current
// edge, f_ext = −∫ p n dl with its derivative ∂f_ext/∂u (element.hpp's pressure_load; docs/segment.md
// "Static load cases"), into the residual as −f_ext.
#include "fitlib/segment/load.hpp"

#include "dofs.hpp"
#include "element.hpp"

namespace fitlib::segment {

void FollowerPressure::add(LoadAssembly& to) const {
  const double pressure = to.lambda() * pressure_MPa_;
  if (pressure == 0.0) return;
  for (std::size_t k = 0; k < mesh_.bottom_edges.size(); ++k) {
    const std::vector<int> en = detail::edge_nodes(mesh_.bottom_edges[k]);
    std::vector<Eigen::Vector2d> x;
    for (int a : en) x.push_back(mesh_.X[a] + to.u(a));
    detail::ElementVector f;
    detail::ElementMatrix Ke;
    detail::pressure_load(x, pressure, f, Ke);
    to.add_bottom_edge(static_cast<int>(k), -f, -Ke);
  }
}

}  // namespace fitlib::segment
