// Implicit dynamics of the segment (inertia.hpp; docs/segment.md "Inertia").
#include "inertia.hpp"

#include <cmath>
#include <utility>

#include "element.hpp"

namespace fitlib::segment::detail {

std::vector<double> lumped_masses(const Mesh& m, double density_t_mm3) {
  std::vector<double> mass(m.node_count(), 0.0);
  const int npe = m.nodes_per_element;
  double N[8], dxi[8], deta[8];
  for (int e = 0; e < m.element_count(); ++e) {
    double diagonal[8] = {}, total = 0.0, element_mass = 0.0;
    for (const GaussPoint& g : gauss_rule(3)) {  // exact for N_a² on a parallelogram
      shape(npe, g.xi, g.eta, N, dxi, deta);
      const double dA = reference_jacobian(m, e, g.xi, g.eta) * g.weight;
      element_mass += density_t_mm3 * dA;
      for (int a = 0; a < npe; ++a) diagonal[a] += density_t_mm3 * N[a] * N[a] * dA;
    }
    for (int a = 0; a < npe; ++a) total += diagonal[a];
    for (int a = 0; a < npe; ++a) mass[m.elements[e][a]] += element_mass * diagonal[a] / total;
  }
  return mass;
}

BackwardEulerInertia::BackwardEulerInertia(std::vector<double> mass_t_mm, FrameMotion frame)
    : mass_(std::move(mass_t_mm)), frame_(std::move(frame)),
      frame_u_(mass_.size(), Eigen::Vector2d::Zero()), w_n_(frame_u_), v_n_(frame_u_) {}

void BackwardEulerInertia::begin(const LoadStep& step) {
  if (pending_) take_history(*step.u_mm), pending_ = false;
  dt_s_ = step.dt_s;
  if (frame_) frame_(step.lambda, frame_u_);
}

void BackwardEulerInertia::add(LoadAssembly& to) const {
  if (!active()) return;
  for (int n = 0; n < to.node_count(); ++n) {
    if (!to.moves(n)) continue;
    to.add_node_force(n, force(n, to.u(n)));
    to.add_node_stiffness(n, stiffness(n));
  }
}

Eigen::Vector2d BackwardEulerInertia::force(int a, const Eigen::Vector2d& u) const {
  if (!active()) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d w = u - frame_u_[a];
  return mass_[a] * (w - w_n_[a] - dt_s_ * v_n_[a]) / (dt_s_ * dt_s_);
}

void BackwardEulerInertia::take_history(const std::vector<Eigen::Vector2d>& u) {
  for (std::size_t a = 0; a < u.size(); ++a) {
    const Eigen::Vector2d w = u[a] - frame_u_[a];
    v_n_[a] = active() ? Eigen::Vector2d((w - w_n_[a]) / dt_s_) : Eigen::Vector2d::Zero();
    w_n_[a] = w;
  }
}

}  // namespace fitlib::segment::detail
