#pragma once
// Implicit dynamics of the segment (PhysicsOptions::inertia; docs/segment.md "Inertia"): the rubber's
// lumped mass on the nodes' motion relative to the cord-line frame, integrated by backward Euler.
// With w = u − u_frame(λ) (u_frame: each node carried rigidly with its column's cord frame,
// StaticProblem::frame_motion) the inertia force at t_{n+1} is
//     m a = m (w − w_n − Δt v_n) / Δt²,   v_{n+1} = (w − w_n) / Δt,
// and its tangent m / Δt² on the diagonal: a small (cut) step is stiffer, not softer. A load
// (segment/load.hpp) the solver adds after the problem's when PhysicsOptions::inertia is on.
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "fitlib/segment/load.hpp"
#include "fitlib/segment/mesh.hpp"

namespace fitlib::segment::detail {

// Lumped nodal masses (t per mm of width) of density ρ (t/mm³) by diagonal scaling (Hinton, Rock &
// Zienkiewicz 1976): m_a = m_e M_aa / Σ_b M_bb, M the consistent mass. Row sums would give the
// 8-node serendipity element's corners negative masses (−1/12 of a rectangle's mass each).
std::vector<double> lumped_masses(const Mesh& mesh, double density_t_mm3);

class BackwardEulerInertia final : public Load {
 public:
  using FrameMotion = std::function<void(double lambda, std::vector<Eigen::Vector2d>& u_mm)>;
  // `frame` may be empty: the motion is then measured from the reference (a fixed frame).
  BackwardEulerInertia(std::vector<double> mass_t_mm, FrameMotion frame);

  // Before an increment's iterations: the last converged increment's motion becomes the history
  // (when the next one begins, so the final snapshot still sees the last increment's step), then
  // the frame's displacement at the target λ and the step (s).
  void begin(const LoadStep& step) override;
  void commit(const ConvergedLoads&) override { pending_ = true; }
  // m·a of every node with a free component into the residual (a cord-line node follows its frame
  // exactly), m/Δt² onto the diagonal of its free equations (the mass is isotropic, so a node's
  // rotated basis leaves it diagonal and uncoupled from the prescribed components).
  void add(LoadAssembly& to) const override;

  bool active() const { return dt_s_ > 0.0; }
  // Inertia force (global, N/mm) of node a at displacement u (global, mm), and its stiffness m/Δt².
  Eigen::Vector2d force(int node, const Eigen::Vector2d& u_mm) const;
  double stiffness(int node) const { return active() ? mass_[node] / (dt_s_ * dt_s_) : 0.0; }

 private:
  // The step's relative motion at the converged displacements u (global, per node) as the history.
  void take_history(const std::vector<Eigen::Vector2d>& u_mm);

  std::vector<double> mass_;
  FrameMotion frame_;
  std::vector<Eigen::Vector2d> frame_u_, w_n_, v_n_;
  double dt_s_ = 0.0;
  bool pending_ = false;  // a converged increment's motion not yet taken as the history
};

}  // namespace fitlib::segment::detail
