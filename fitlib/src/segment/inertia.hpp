#pragma once
// Implicit dynamics of the segment (SolverKnobs::inertia; docs/segment.md "Inertia"): the rubber's
// lumped mass on the nodes' motion relative to the cord-line frame, integrated by backward Euler.
// With w = u − u_frame(λ) (u_frame: each node carried rigidly with its column's cord frame,
// StaticProblem::frame_motion) the inertia force at t_{n+1} is
//     m a = m (w − w_n − Δt v_n) / Δt²,   v_{n+1} = (w − w_n) / Δt,
// and its tangent m / Δt² on the diagonal: a small (cut) step is stiffer, not softer.
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "fitlib/segment/mesh.hpp"

namespace fitlib::segment::detail {

// Lumped nodal masses (t per mm of width) of density ρ (t/mm³) by diagonal scaling (Hinton, Rock &
// Zienkiewicz 1976): m_a = m_e M_aa / Σ_b M_bb, M the consistent mass. Row sums would give the
// 8-node serendipity element's corners negative masses (−1/12 of a rectangle's mass each).
std::vector<double> lumped_masses(const Mesh& mesh, double density_t_mm3);

class BackwardEulerInertia {
 public:
  using FrameMotion = std::function<void(double lambda, std::vector<Eigen::Vector2d>& u_mm)>;
  // `frame` may be empty: the motion is then measured from the reference (a fixed frame).
  BackwardEulerInertia(std::vector<double> mass_t_mm, FrameMotion frame);

  // Before an increment's iterations: the frame's displacement at the target λ and the step (s).
  void begin(double lambda, double dt_s);
  bool active() const { return dt_s_ > 0.0; }
  // Inertia force (global, N/mm) of node a at displacement u (global, mm), and its stiffness m/Δt².
  Eigen::Vector2d force(int node, const Eigen::Vector2d& u_mm) const;
  double stiffness(int node) const { return active() ? mass_[node] / (dt_s_ * dt_s_) : 0.0; }
  // After convergence at the displacements u (global, per node): the step's relative motion becomes
  // the history.
  void commit(const std::vector<Eigen::Vector2d>& u_mm);

 private:
  std::vector<double> mass_;
  FrameMotion frame_;
  std::vector<Eigen::Vector2d> frame_u_, w_n_, v_n_;
  double dt_s_ = 0.0;
};

}  // namespace fitlib::segment::detail
