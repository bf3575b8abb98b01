#pragma once
// The segment's element loop (solver.cpp): each element's internal force and consistent tangent
// through the material-point contract (element.hpp) and the loads acting at its integration points,
// then the other loads (segment/load.hpp) through LoadAssembly, added into the residual and the
// tangent's slots in the nodes' local bases. The one place that loops over elements. Threaded over
// elements, bit-identical whatever the thread count.
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "dofs.hpp"
#include "element.hpp"
#include "worker_pool.hpp"
#include "fitlib/segment/solver.hpp"

namespace fitlib::segment::detail {

// One element's response as the scatter adds it: force and tangent in its nodes' local bases,
// its points' states, and whether every point responded (the element loop's per-element buffer).
struct ElementBuffer {
  std::vector<Eigen::Vector2d> X, u;
  detail::ElementVector f;
  detail::ElementMatrix K;
  std::vector<detail::ElementState> states;
  bool ok = false;
};

class Assembler {
 public:
  // `loads`: the problem's and the solver's own (inertia), in the order they are added.
  Assembler(const StaticProblem& p, const Dofs& d, int order, bool f_bar, detail::WorkerPool& pool,
            std::vector<Load*> loads);

  std::size_t points_per_element() const { return rule_.size(); }
  // The step the point states are updated over (state_n → state_next).
  void set_step(const double* state_n, double* state_next, double dt_s) {
    state_n_ = state_n, state_next_ = state_next, dt_s_ = dt_s;
  }
  void set_offsets(const std::vector<std::size_t>* offset) { offset_ = offset; }
  // Per equation, the slot of K_ii (LoadAssembly::add_node_stiffness).
  void set_diagonal(const std::vector<int>* diagonal) { diagonal_ = diagonal; }
  // NewtonOptions::linearised_pressure: tangent assemblies keep each point's F, and one that
  // `follows_step` a step from the last takes the pressure term linearised over it (element.hpp).
  void set_linearised_pressure(bool on) {
    last_F_.assign(on ? p_.mesh->element_count() * rule_.size() : 0, Eigen::Matrix2d::Identity());
  }
  void set_follows_step(bool follows) const { follows_step_ = follows; }

  Eigen::Vector2d u_of(const Eigen::VectorXd& q, int node) const { return d_.R[node] * q.segment<2>(2 * node); }

  // One element's response at q, as run() computes it (the failure diagnosis).
  bool element_at(const Eigen::VectorXd& q, int e, detail::ElementVector& f, detail::ElementMatrix* Ke,
                  std::vector<detail::ElementState>* states = nullptr) const;
  const PlaneStrainLaw& law_of(int e) const { return p_.law_of(e); }
  detail::ElementStep step_of(int e) const {
    const std::size_t at = (*offset_)[e];
    return {state_n_ + at, state_next_ + at, dt_s_, p_.temperature_C};
  }

  // Residual (local components, all dofs) and, if asked, the free-free tangent into the pattern's
  // values and K_fp·dq_p into coupling. Returns the failing element, or −1. The elements' responses
  // are computed on the pool into their buffers, then added in element order up to the first
  // failing one, exactly as a serial loop would (bit-identical whatever the thread count).
  int run(const Eigen::VectorXd& q, double lambda, const Eigen::VectorXd* dq_p, Eigen::VectorXd& r,
          Pattern* K, Eigen::VectorXd* coupling,
          std::vector<std::vector<IntegrationPointStress>>* states = nullptr) const;
  // Each assembly keeps its points' stresses (per element; those of the elements before a failing
  // one): the converged increment's are its last assembly's, at the converged q, so reading them
  // here costs no element loop of its own.
  const std::vector<std::vector<IntegrationPointStress>>& last_points() const { return last_points_; }

  // Per element, the point loads' ∫ b dV at q (global; empty without one), at the λ of the last
  // assembly.
  std::vector<Eigen::Vector2d> point_load_forces(const Eigen::VectorXd& q) const;

  // Every load's begin, before an increment's iterations to λ over dt from q (serial).
  void begin(const Eigen::VectorXd& q, double lambda, double dt_s) const;
  // Every load's commit at the converged q (serial).
  void commit(const Eigen::VectorXd& q, double lambda) const;

  // Per node, the displacement at q (global).
  std::vector<Eigen::Vector2d> displacements(const Eigen::VectorXd& q) const;
  bool moves(int n) const { return d_.eq[2 * n] >= 0 || d_.eq[2 * n + 1] >= 0; }

 private:
  // Element e's response at q into a buffer (runs on any of the pool's threads: writes only that
  // buffer and element e's trial states).
  void respond(const Eigen::VectorXd& q, int e, bool tangent, ElementBuffer& b) const;
  mutable std::vector<std::vector<IntegrationPointStress>> last_points_;

  // f and K from global components to the nodes' local bases (Rᵀf, R_aᵀ K_ab R_b); a node without
  // a constraint has R = I and is left as it is.
  void to_local(const int* nodes, int n, detail::ElementVector& f, detail::ElementMatrix* K) const;

  class Pass;  // one assembly's LoadAssembly (assembler.cpp)

  // The shape functions at the rule's points, each element's reference points (∂N/∂X, dV: the
  // reference does not move) and their volumes dV (the body forces' and the point loads' weights).
  void point_weights();

  // The point loads at element e's points (global components): −∫ N_a b dV into the force,
  // −∫ N_a N_b ∂b/∂x dV into the tangent.
  void add_point_loads(int e, const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& u,
                       detail::ElementVector& f, detail::ElementMatrix* K) const;

  // Dead body forces b (N/mm³ of reference volume, per element) as consistent nodal loads
  // −∫ N_a b dV (the residual is internal minus external force).
  void add_body_forces(const std::vector<Eigen::Vector2d>& b, Eigen::VectorXd& r) const;

  // Every integration point's current position at q (element by element, in the rule's order).
  std::vector<Eigen::Vector2d> point_positions(const Eigen::VectorXd& q) const;

  // Adds an element's (or edge's) local force and tangent: free-free entries into K's slots,
  // free-prescribed ones times the prescribed step into coupling (the predictor).
  template <typename Nodes>
  void scatter(const Nodes& nodes, const detail::ElementVector& f, const detail::ElementMatrix* Ke, const Eigen::VectorXd* dq_p,
               Eigen::VectorXd& r, Pattern* K, const std::vector<int>* slots, Eigen::VectorXd* coupling) const;

  const StaticProblem& p_;
  const Dofs& d_;
  std::vector<detail::GaussPoint> rule_;
  bool f_bar_ = false;
  detail::WorkerPool& pool_;
  mutable std::vector<ElementBuffer> buffers_;
  const std::vector<std::size_t>* offset_ = nullptr;
  const double* state_n_ = nullptr;
  double* state_next_ = nullptr;
  double dt_s_ = 0.0;
  std::vector<Load*> loads_, point_loads_;  // all, and those acting at the integration points
  std::vector<double> shape_, volume_;  // point_weights(): N_a per point of the rule, dV per element and point
  std::vector<detail::ReferencePoint> reference_;  // point_weights(): per element, its rule's points
  mutable double prepared_at_ = std::numeric_limits<double>::quiet_NaN();  // the λ the loads were prepared at
  const std::vector<int>* diagonal_ = nullptr;
  mutable std::vector<Eigen::Matrix2d> last_F_;  // per element and point (empty: linearised_pressure off)
  mutable bool follows_step_ = false;
};

}  // namespace fitlib::segment::detail
