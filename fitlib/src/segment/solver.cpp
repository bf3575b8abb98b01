#include "fitlib/segment/solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <thread>

#include <Eigen/LU>

#include "diagnosis.hpp"
#include "element.hpp"
#include "grouped_ldlt.hpp"
#include "inertia.hpp"
#include "linear_solver.hpp"
#include "worker_pool.hpp"
#include "fitlib/core/error.hpp"

namespace fitlib::segment {

int gauss_order(const Mesh& mesh, Integration integration) {
  return (mesh.nodes_per_element == 8 && integration != Integration::reduced) ? 3 : 2;
}

namespace {
using detail::ElementMatrix;
using detail::ElementVector;
using detail::LinearSolver;
using detail::SparseMatrix;

// An increment that failed from the rotated predictor is retaken without its rotation terms only
// when they moved the start by more than this (Euclidean norm over the nodes).
constexpr double kRetakeRotation_mm = 1e-4;

// Global unknowns: two local components per node; a constrained node's basis is rotated.
struct Dofs {
  std::vector<Eigen::Matrix2d> R;  // columns = local basis vectors
  std::vector<int> eq;             // 2 per node: equation number, or −1 when prescribed
  std::vector<int> constraint;     // per node: index in the problem's constraints, or −1
  int equations = 0;
};

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

// All integration points' states in one contiguous block: element e's points start at offset[e].
struct StateBlock {
  std::vector<std::size_t> offset;
  std::vector<double> committed, trial;
};

StateBlock initial_states(const StaticProblem& p, std::size_t points_per_element) {
  const Mesh& m = *p.mesh;
  StateBlock b;
  for (int e = 0; e < m.element_count(); ++e) {
    const PlaneStrainLaw& law = *p.laws[static_cast<int>(m.roles[e])];
    b.offset.push_back(b.committed.size());
    const std::vector<double> virgin = law.initial_state();
    for (std::size_t q = 0; q < points_per_element; ++q) b.committed.insert(b.committed.end(), virgin.begin(), virgin.end());
  }
  b.trial = b.committed;
  return b;
}

// The free-free tangent's sparsity, built once: per element and per bottom edge, the position in
// K's value array of each local (row dof, column dof) pair, or −1 when either is prescribed.
struct Pattern {
  SparseMatrix K;
  std::vector<std::vector<int>> element_slots, edge_slots;
};

std::vector<int> local_dofs(const std::vector<int>& nodes, const Dofs& d) {
  std::vector<int> eq;
  for (int n : nodes)
    for (int i = 0; i < 2; ++i) eq.push_back(d.eq[2 * n + i]);
  return eq;
}

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

// Per equation: the slot of K_ii in K's values.
std::vector<int> diagonal_slots(const SparseMatrix& K) {
  std::vector<int> slots;
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  for (int j = 0; j < K.cols(); ++j)
    slots.push_back(static_cast<int>(std::lower_bound(inner + outer[j], inner + outer[j + 1], j) - inner));
  return slots;
}

// The pattern with the free equations renumbered in the node groups' AMD order (grouped_ldlt.hpp),
// the elimination order of the symmetric solver.
Pattern ordered_pattern(const Mesh& m, Dofs& d) {
  const std::vector<int> order = detail::grouped_amd_order(build_pattern(m, d).K);
  std::vector<int> position(order.size());
  for (std::size_t p = 0; p < order.size(); ++p) position[order[p]] = static_cast<int>(p);
  for (int& e : d.eq)
    if (e >= 0) e = position[e];
  return build_pattern(m, d);
}

// One element's response as the scatter adds it: force and tangent in its nodes' local bases,
// its points' states, and whether every point responded (the element loop's per-element buffer).
struct ElementBuffer {
  std::vector<Eigen::Vector2d> X, u;
  ElementVector f;
  ElementMatrix K;
  std::vector<detail::ElementState> states;
  bool ok = false;
};

class Assembler {
 public:
  Assembler(const StaticProblem& p, const Dofs& d, int order, bool f_bar, detail::WorkerPool& pool)
      : p_(p), d_(d), rule_(detail::gauss_rule(order)), f_bar_(f_bar), pool_(pool),
        buffers_(pool.threads() > 1 ? p.mesh->element_count() : 1) {
    if (p.body_force || p.following_force.at) point_weights();
  }

  std::size_t points_per_element() const { return rule_.size(); }
  // The step the point states are updated over (state_n → state_next).
  void set_step(const double* state_n, double* state_next, double dt_s) {
    state_n_ = state_n, state_next_ = state_next, dt_s_ = dt_s;
  }
  void set_offsets(const std::vector<std::size_t>* offset) { offset_ = offset; }
  // SolverKnobs::inertia (segment/inertia.hpp); `diagonal`: per equation, the slot of K_ii.
  void set_inertia(const detail::BackwardEulerInertia* inertia, const std::vector<int>* diagonal) {
    inertia_ = inertia, diagonal_ = diagonal;
  }

  Eigen::Vector2d u_of(const Eigen::VectorXd& q, int node) const { return d_.R[node] * q.segment<2>(2 * node); }

  // One element's response at q, as run() computes it (the failure diagnosis).
  bool element_at(const Eigen::VectorXd& q, int e, ElementVector& f, ElementMatrix* Ke,
                  std::vector<detail::ElementState>* states = nullptr) const {
    const Mesh& m = *p_.mesh;
    std::vector<Eigen::Vector2d> X, u;
    for (int a = 0; a < m.nodes_per_element; ++a) X.push_back(m.X[m.elements[e][a]]), u.push_back(u_of(q, m.elements[e][a]));
    const bool ok = detail::element_response(X, u, law_of(e), rule_, step_of(e), f, Ke, states, f_bar_);
    if (ok) add_following(e, X, u, f, Ke);
    return ok;
  }
  const PlaneStrainLaw& law_of(int e) const { return *p_.laws[static_cast<int>(p_.mesh->roles[e])]; }
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
          std::vector<std::vector<IntegrationPointStress>>* states = nullptr) const {
    const Mesh& m = *p_.mesh;
    r.setZero(2 * m.node_count());
    if (K) std::fill(K->K.valuePtr(), K->K.valuePtr() + K->K.nonZeros(), 0.0);
    if (coupling) coupling->setZero(d_.equations);
    if (states) states->assign(m.element_count(), {});
    if (p_.following_force.prepare && lambda != following_at_) p_.following_force.prepare(lambda), following_at_ = lambda;
    // One thread: each element computed into one buffer and added at once (the same operations in
    // the same order as with the team, without a pass over all buffers: cache).
    const bool team = pool_.threads() > 1;
    if (team) pool_.for_each(m.element_count(), [&](int e) { respond(q, e, K != nullptr, states != nullptr, buffers_[e]); });
    for (int e = 0; e < m.element_count(); ++e) {
      const ElementBuffer& b = team ? buffers_[e] : buffers_[0];
      if (!team) respond(q, e, K != nullptr, states != nullptr, buffers_[0]);
      if (!b.ok) return e;
      scatter(m.elements[e], b.f, K ? &b.K : nullptr, dq_p, r, K, K ? &K->element_slots[e] : nullptr, coupling);
      if (states)
        for (const auto& s : b.states) (*states)[e].push_back({s.X_mm, s.cauchy_MPa, s.sigma33_MPa, s.piola_MPa, s.F});
    }
    const double pressure = lambda * p_.pressure_MPa;
    if (pressure != 0.0)
      for (std::size_t k = 0; k < m.bottom_edges.size(); ++k) {
        const std::vector<int> en = edge_nodes(m.bottom_edges[k]);
        std::vector<Eigen::Vector2d> x;
        for (int a : en) x.push_back(m.X[a] + u_of(q, a));
        ElementVector f;
        ElementMatrix Ke;
        detail::pressure_load(x, pressure, f, Ke);
        f = -f;
        Ke = -Ke;
        to_local(en.data(), static_cast<int>(en.size()), f, K ? &Ke : nullptr);
        scatter(en.data(), f, K ? &Ke : nullptr, dq_p, r, K, K ? &K->edge_slots[k] : nullptr, coupling);
      }
    if (p_.body_force) add_body_forces(lambda, r);
    if (p_.nodal_force) {
      if (lambda != nodal_at_) p_.nodal_force(lambda, nodal_), nodal_at_ = lambda;  // dead: a function of λ
      for (std::size_t n = 0; n < nodal_.size(); ++n) r.segment<2>(2 * n) -= d_.R[n].transpose() * nodal_[n];
    }
    if (inertia_ && inertia_->active()) add_inertia(q, r, K);  // dynamics hook (SolverKnobs::inertia)
    return -1;
  }

  // Per element, the following force's ∫ b dV at q (global; empty without one), at the λ of the
  // last assembly.
  std::vector<Eigen::Vector2d> following_forces(const Eigen::VectorXd& q) const {
    const Mesh& m = *p_.mesh;
    std::vector<Eigen::Vector2d> out;
    if (!p_.following_force.at) return out;
    const int npe = m.nodes_per_element;
    std::vector<Eigen::Vector2d> X(npe), u(npe);
    ElementVector f;
    for (int e = 0; e < m.element_count(); ++e) {
      for (int a = 0; a < npe; ++a) X[a] = m.X[m.elements[e][a]], u[a] = u_of(q, m.elements[e][a]);
      f.setZero(2 * npe);
      add_following(e, X, u, f, nullptr);
      Eigen::Vector2d total = Eigen::Vector2d::Zero();
      for (int a = 0; a < npe; ++a) total -= f.segment<2>(2 * a);
      out.push_back(total);
    }
    return out;
  }

  // StaticProblem::following_force's commit at every integration point's position at q (serial).
  void commit_following(const Eigen::VectorXd& q) const {
    if (!p_.following_force.commit) return;
    const Mesh& m = *p_.mesh;
    const int npe = m.nodes_per_element;
    for (int e = 0; e < m.element_count(); ++e)
      for (std::size_t g = 0; g < rule_.size(); ++g) {
        const double* N = shape_.data() + g * npe;
        Eigen::Vector2d x = Eigen::Vector2d::Zero();
        for (int a = 0; a < npe; ++a) x += N[a] * (m.X[m.elements[e][a]] + u_of(q, m.elements[e][a]));
        p_.following_force.commit(e, static_cast<int>(g), x);
      }
  }

  // Per node, the inertia force m·a at q (global; empty without inertia).
  std::vector<Eigen::Vector2d> inertia_forces(const Eigen::VectorXd& q) const {
    std::vector<Eigen::Vector2d> f;
    for (int n = 0; inertia_ && n < p_.mesh->node_count(); ++n)
      f.push_back(moves(n) ? inertia_->force(n, u_of(q, n)) : Eigen::Vector2d::Zero());
    return f;
  }

 private:
  // Element e's response at q into a buffer (runs on any of the pool's threads: writes only that
  // buffer and element e's trial states).
  void respond(const Eigen::VectorXd& q, int e, bool tangent, bool states, ElementBuffer& b) const {
    const Mesh& m = *p_.mesh;
    const int npe = m.nodes_per_element;
    const int* nodes = m.elements[e].data();
    b.X.resize(npe), b.u.resize(npe);
    for (int a = 0; a < npe; ++a) b.X[a] = m.X[nodes[a]], b.u[a] = u_of(q, nodes[a]);
    b.ok = detail::element_response(b.X, b.u, law_of(e), rule_, step_of(e), b.f, tangent ? &b.K : nullptr,
                                    states ? &b.states : nullptr, f_bar_);
    if (b.ok) add_following(e, b.X, b.u, b.f, tangent ? &b.K : nullptr);
    if (b.ok) to_local(nodes, npe, b.f, tangent ? &b.K : nullptr);
  }

  // f and K from global components to the nodes' local bases (Rᵀf, R_aᵀ K_ab R_b); a node without
  // a constraint has R = I and is left as it is.
  void to_local(const int* nodes, int n, ElementVector& f, ElementMatrix* K) const {
    for (int a = 0; a < n; ++a)
      if (d_.constraint[nodes[a]] >= 0) f.segment<2>(2 * a) = d_.R[nodes[a]].transpose() * f.segment<2>(2 * a);
    if (!K) return;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        if (d_.constraint[nodes[a]] >= 0 || d_.constraint[nodes[b]] >= 0) {
          const Eigen::Matrix2d k = d_.R[nodes[a]].transpose() * K->block<2, 2>(2 * a, 2 * b) * d_.R[nodes[b]];
          K->block<2, 2>(2 * a, 2 * b) = k;
        }
  }

  // The shape functions at the rule's points and each point's reference volume dV (the body
  // forces' and the following force's weights; the shape functions are the same in every element).
  void point_weights() {
    const Mesh& m = *p_.mesh;
    const int npe = m.nodes_per_element;
    double N[8], dxi[8], deta[8];
    for (const auto& g : rule_) {
      detail::shape(npe, g.xi, g.eta, N, dxi, deta);
      shape_.insert(shape_.end(), N, N + npe);
    }
    for (int e = 0; e < m.element_count(); ++e)
      for (const auto& g : rule_) volume_.push_back(reference_jacobian(m, e, g.xi, g.eta) * g.weight);
  }

  // StaticProblem::following_force at element e's points (global components): −∫ N_a b dV into the
  // force, −∫ N_a N_b ∂b/∂x dV into the tangent.
  void add_following(int e, const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& u,
                     ElementVector& f, ElementMatrix* K) const {
    if (!p_.following_force.at) return;
    const int npe = p_.mesh->nodes_per_element;
    Eigen::Vector2d b;
    Eigen::Matrix2d db;
    for (std::size_t g = 0; g < rule_.size(); ++g) {
      const double* N = shape_.data() + g * npe;
      Eigen::Vector2d x = Eigen::Vector2d::Zero();
      for (int a = 0; a < npe; ++a) x += N[a] * (X[a] + u[a]);
      if (!p_.following_force.at(e, static_cast<int>(g), x, b, db)) continue;
      const double dV = volume_[e * rule_.size() + g];
      for (int a = 0; a < npe; ++a) {
        f.segment<2>(2 * a) -= N[a] * dV * b;
        for (int c = 0; K && c < npe; ++c) K->block<2, 2>(2 * a, 2 * c) -= N[a] * N[c] * dV * db;
      }
    }
  }

  // Dead body forces b (N/mm³ of reference volume, per element) as consistent nodal loads
  // −∫ N_a b dV (the residual is internal minus external force).
  void add_body_forces(double lambda, Eigen::VectorXd& r) const {
    const Mesh& m = *p_.mesh;
    if (lambda != body_at_) {  // dead: a function of λ, asked once per λ (not per Newton iteration)
      body_.assign(m.element_count(), Eigen::Vector2d::Zero());
      p_.body_force(lambda, body_);
      body_at_ = lambda;
    }
    const int npe = m.nodes_per_element;
    for (int e = 0; e < m.element_count(); ++e) {
      if (body_[e].isZero(0.0)) continue;
      for (std::size_t g = 0; g < rule_.size(); ++g)
        for (int a = 0; a < npe; ++a) {
          const int n = m.elements[e][a];
          r.segment<2>(2 * n) -= d_.R[n].transpose() * ((shape_[g * npe + a] * volume_[e * rule_.size() + g]) * body_[e]);
        }
    }
  }

  bool moves(int n) const { return d_.eq[2 * n] >= 0 || d_.eq[2 * n + 1] >= 0; }

  // m·a of every node with a free component into the residual (a cord-line node follows its frame
  // exactly), m/Δt² onto the diagonal of its free equations (the mass is isotropic, so a node's
  // rotated basis leaves it diagonal and uncoupled from the prescribed components).
  void add_inertia(const Eigen::VectorXd& q, Eigen::VectorXd& r, Pattern* K) const {
    for (int n = 0; n < p_.mesh->node_count(); ++n) {
      if (!moves(n)) continue;
      r.segment<2>(2 * n) += d_.R[n].transpose() * inertia_->force(n, u_of(q, n));
      for (int k = 0; K && k < 2; ++k)
        if (d_.eq[2 * n + k] >= 0) K->K.valuePtr()[(*diagonal_)[d_.eq[2 * n + k]]] += inertia_->stiffness(n);
    }
  }

  // Adds an element's (or edge's) local force and tangent: free-free entries into K's slots,
  // free-prescribed ones times the prescribed step into coupling (the predictor).
  template <typename Nodes>
  void scatter(const Nodes& nodes, const ElementVector& f, const ElementMatrix* Ke, const Eigen::VectorXd* dq_p,
               Eigen::VectorXd& r, Pattern* K, const std::vector<int>* slots, Eigen::VectorXd* coupling) const {
    const int n = static_cast<int>(f.size() / 2);
    for (int a = 0; a < n; ++a) r.segment<2>(2 * nodes[a]) += f.segment<2>(2 * a);
    if (!Ke) return;
    double* values = K->K.valuePtr();
    const int width = 2 * n;
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 2; ++i) {
        const int row = d_.eq[2 * nodes[a] + i];
        if (row < 0) continue;
        for (int b = 0; b < n; ++b)
          for (int j = 0; j < 2; ++j) {
            const int slot = (*slots)[(2 * a + i) * width + 2 * b + j];
            if (slot >= 0) values[slot] += (*Ke)(2 * a + i, 2 * b + j);
            else if (dq_p) (*coupling)(row) += (*Ke)(2 * a + i, 2 * b + j) * (*dq_p)(2 * nodes[b] + j);
          }
      }
  }

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
  mutable std::vector<Eigen::Vector2d> body_, nodal_;  // the dead loads at body_at_, nodal_at_
  mutable double body_at_ = std::numeric_limits<double>::quiet_NaN(), nodal_at_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> shape_, volume_;  // point_weights(): N_a per point of the rule, dV per element and point
  mutable double following_at_ = std::numeric_limits<double>::quiet_NaN();  // the λ following_force was prepared at
  const detail::BackwardEulerInertia* inertia_ = nullptr;
  const std::vector<int>* diagonal_ = nullptr;
};

double free_norm(const Eigen::VectorXd& r, const Dofs& d, bool free) {
  double s = 0.0;
  for (int i = 0; i < r.size(); ++i)
    if ((d.eq[i] >= 0) == free) s += r(i) * r(i);
  return std::sqrt(s);
}

// One load increment's Newton iterations (docs/segment.md §Solver). With `reuse_tangent` the
// factorisation in hand is kept while the free residual contracts by `reuse_contraction` per
// iteration (modified Newton: a residual-only assembly and a back-substitution); a slower
// contraction asks for a fresh tangent at the next iterate, and a step on a kept factorisation
// that does not lower the residual is retaken from its start on a fresh one. A step on a fresh
// tangent that lowers neither the residual norm nor the energy measure |Δq·r| below 0.8 of its
// start (a near-incompressible body's residual may rise on the way), or inverts an element, is
// retaken on the shifted tangent K + μ·diag|K| (`levenberg`), and beyond the largest shift halved up
// to five times.
struct NewtonOutcome {
  bool converged = false;
  int iterations = 0, factorizations = 0, assemblies = 0, bad_element = -1;
  double residual = std::numeric_limits<double>::infinity();
};

class Newton {
 public:
  Newton(const Assembler& a, Pattern& K, LinearSolver& linear, const Dofs& d, const SolverKnobs& knobs,
         Eigen::VectorXd& q)
      : a_(a), K_(K), linear_(linear), d_(d), knobs_(knobs), q_(q), diagonal_(diagonal_slots(K.K)) {}

  // The node carrying the largest free residual component of the last assembly (-1: none).
  int worst_node() const {
    int worst = -1;
    double largest = -1.0;
    for (int i = 0; i < r_.size(); ++i)
      if (d_.eq[i] >= 0 && std::abs(r_(i)) > largest) largest = std::abs(r_(i)), worst = i / 2;
    return worst;
  }

  // Added to the predictor's step (local components; empty: none): the second-order part of the
  // nodes' finite rotation with the loading.
  void set_rotation(Eigen::VectorXd rotation) { rotation_ = std::move(rotation); }
  // Per equation, the slot of K_ii in K's values.
  const std::vector<int>& diagonal() const { return diagonal_; }

  // The iterate with the lowest residual of the last solve (empty before one).
  const Eigen::VectorXd& best_iterate() const { return best_q_; }

  // From the converged q to load level λ; q_start holds the prescribed components at λ and the
  // free ones' start (`extrapolated`: the last increment's motion extrapolated, iterated on the
  // kept factorisation with `reuse_tangent`, else on a fresh tangent; otherwise the last converged
  // values, and the first iteration is the linear predictor).
  NewtonOutcome solve(double lambda, const Eigen::VectorXd& q_start, bool extrapolated) {
    NewtonOutcome o = iterate(lambda, q_start, extrapolated);
    if (o.converged || !extrapolated) return o;
    const NewtonOutcome extrapolation = o;
    Eigen::VectorXd linear_start = q_start;  // the extrapolation led astray: the linear predictor
    for (int i = 0; i < q_start.size(); ++i)
      if (d_.eq[i] >= 0) linear_start(i) = q_last_(i);
    q_ = q_last_;
    o = iterate(lambda, linear_start, false);
    o.iterations += extrapolation.iterations, o.factorizations += extrapolation.factorizations;
    o.assemblies += extrapolation.assemblies;
    return o;
  }

 private:
  NewtonOutcome iterate(double lambda, const Eigen::VectorXd& q_start, bool extrapolated) {
    const double inf = std::numeric_limits<double>::infinity();
    NewtonOutcome o;
    bool predictor = !extrapolated, fresh = predictor || !knobs_.reuse_tangent, stale_step = false;
    const Eigen::VectorXd dq_p = q_start - q_;
    q_last_ = q_;
    if (extrapolated) q_ = q_start;
    Eigen::VectorXd q_prev, dq, rhs(d_.equations);
    double res_prev = inf, alpha = 1.0, energy_prev = 0.0, best = inf, mu = 0.0;
    bool shifted_retake = false;
    double retake_res = inf;
    int since_best = 0;
    double best_iterate_res = inf;
    best_q_.resize(0);
    kept_ = false;
    bool restored = false;  // r_ and K_ hold q_'s, kept from before its step (no assembly needed)
    for (int it = 0; it < knobs_.max_iterations; ++it) {
      // (A restored start leaves the point states at the rejected iterate's: giving up there
      // re-evaluates them before q_ is accepted.)
      const bool states_elsewhere = restored;
      if (restored) o.bad_element = -1;
      else o.bad_element = assemble(q_, lambda, predictor ? &dq_p : nullptr, fresh, &o);
      restored = false;
      const double res = o.bad_element >= 0 ? inf : free_norm(r_, d_, true);
      o.residual = res;
      const bool worse = !(res < res_prev) && !(std::isfinite(res) && energy(dq) < 0.8 * energy_prev);
      if (worse && std::isfinite(res_prev) && stale_step) {
        q_ = q_prev, fresh = true, stale_step = false, res_prev = inf;
        continue;
      }
      if (worse && std::isfinite(res_prev) && alpha == 1.0 && knobs_.levenberg > 0.0 && mu < 1e4 * knobs_.levenberg) {
        if (++since_best > knobs_.stall_iterations) return o;
        mu = mu > 0.0 ? 10.0 * mu : knobs_.levenberg;  // retake the step from its start on K + μ·diag|K|
        q_ = q_prev, fresh = true, res_prev = inf, shifted_retake = true;
        restored = restore_kept();  // the retake's start was an iterate: its K and r need no assembly
        continue;
      }
      if (worse && std::isfinite(res_prev) && alpha > 1.0 / 32.0) {
        if (++since_best > knobs_.stall_iterations) return o;  // halvings count towards the stall
        alpha *= 0.5;
        move(q_prev, dq, alpha);
        continue;
      }
      if (worse && std::isfinite(res_prev) && res_prev <= knobs_.stall_tolerance * (free_norm(r_, d_, false) + 1.0)) {
        q_ = q_prev;  // no step lowers the residual, which is below the loose tolerance: accept its start
        o.bad_element = assemble(q_, lambda, nullptr, false, &o);  // the trial states at q_prev
        o.residual = res_prev;
        o.converged = o.bad_element < 0;
        return o;
      }
      if (!std::isfinite(res)) return o;
      const double scale = free_norm(r_, d_, false) + 1.0;
      // Giving up at this iterate (stalled, or no step to take): accepted at the loose tolerance.
      auto give_up = [&] {
        o.converged = !predictor && res <= knobs_.stall_tolerance * scale;
        if (o.converged && states_elsewhere) o.bad_element = assemble(q_, lambda, nullptr, false, &o);
        o.converged = o.converged && o.bad_element < 0;
        return o;
      };
      if (!predictor && res < best_iterate_res) best_iterate_res = res, best_q_ = q_;  // (the predictor's is the old q)
      if (res < best) best = res, since_best = 0;
      else if (++since_best > knobs_.stall_iterations) return give_up();
      if (!predictor && res <= knobs_.tolerance * scale) {
        o.converged = true;
        return o;
      }
      // After a shifted step the shift follows the residual (switched evolution relaxation).
      if (!shifted_retake && mu > 0.0) mu = mu * res / res_prev < 1e-9 ? 0.0 : mu * res / res_prev;
      if (shifted_retake) retake_res = res;
      else if (res < retake_res) mu = 0.0;  // below the overshoot's start: Newton's basin, no shift
      shifted_retake = false;
      keep(fresh && !predictor && knobs_.levenberg > 0.0);  // before the shift: a retake from here restores it
      if (fresh && mu > 0.0) shift_diagonal(mu);
      for (int i = 0; i < r_.size(); ++i)
        if (d_.eq[i] >= 0) rhs(d_.eq[i]) = -r_(i);
      if (predictor) rhs -= coupling_;
      o.factorizations += fresh;  // of K, or of its symmetric part for GMRES
      // (Modified Newton keeps a factorisation of K for its later steps: no GMRES then.)
      const int krylov = knobs_.reuse_tangent ? 0 : knobs_.krylov_iterations;
      if (!(fresh && linear_.krylov_solve(K_.K, rhs, krylov, knobs_.krylov_tolerance, dq))) {
        if (fresh && !linear_.factorize(K_.K)) return give_up();
        dq = linear_.solve(rhs);
      }
      if (!dq.allFinite()) return give_up();
      const bool slow = stale_step && !(res <= knobs_.reuse_contraction * res_prev);
      stale_step = !fresh;
      q_prev = predictor ? q_start : q_;  // the predictor step is taken whole
      res_prev = predictor ? inf : res;
      energy_prev = std::abs(rhs.dot(dq));
      alpha = 1.0;
      move(q_prev, dq, 1.0);
      if (predictor && rotation_.size() == q_.size()) q_ += rotation_;
      predictor = false;
      fresh = !knobs_.reuse_tangent || slow;
      o.iterations++;
    }
    // Out of assemblies: the last iterate, evaluated (the loop may end on a step not yet assembled,
    // and the committed states must be its own), accepted at the loose tolerance as a stalled one is.
    o.bad_element = assemble(q_, lambda, nullptr, false, &o);
    o.residual = o.bad_element >= 0 ? inf : free_norm(r_, d_, true);
    o.converged = o.residual <= knobs_.stall_tolerance * (free_norm(r_, d_, false) + 1.0);
    return o;
  }

  // The element loop at q: r_, and K_ when `tangent` (the predictor's coupling with `dq_p`).
  int assemble(const Eigen::VectorXd& q, double lambda, const Eigen::VectorXd* dq_p, bool tangent, NewtonOutcome* o) {
    ++o->assemblies;
    return a_.run(q, lambda, dq_p, r_, tangent ? &K_ : nullptr, dq_p ? &coupling_ : nullptr);
  }

  // The unshifted tangent and the residual of the iterate a step is taken from (`valid`: they are
  // its own, not the predictor's linearisation about the last increment's state).
  void keep(bool valid) {
    kept_ = valid;
    if (!valid) return;
    kept_K_.assign(K_.K.valuePtr(), K_.K.valuePtr() + K_.K.nonZeros());
    kept_r_ = r_;
  }
  bool restore_kept() {
    if (!kept_) return false;
    std::copy(kept_K_.begin(), kept_K_.end(), K_.K.valuePtr());
    r_ = kept_r_;
    return true;
  }

  // K_ii += μ |K_ii| (Marquardt's scaling: the shift is unit-free and leaves stiff dofs stiff).
  void shift_diagonal(double mu) {
    double* K = K_.K.valuePtr();
    for (int e = 0; e < d_.equations; ++e) K[diagonal_[e]] += mu * std::abs(K[diagonal_[e]]);
  }

  double energy(const Eigen::VectorXd& dq) const {
    double e = 0.0;
    for (int i = 0; i < r_.size() && dq.size(); ++i)
      if (d_.eq[i] >= 0) e += r_(i) * dq(d_.eq[i]);
    return std::abs(e);
  }
  void move(const Eigen::VectorXd& from, const Eigen::VectorXd& dq, double alpha) {
    q_ = from;
    for (int i = 0; i < q_.size(); ++i)
      if (d_.eq[i] >= 0) q_(i) += alpha * dq(d_.eq[i]);
  }

  const Assembler& a_;
  Pattern& K_;
  LinearSolver& linear_;
  const Dofs& d_;
  const SolverKnobs& knobs_;
  Eigen::VectorXd& q_;
  Eigen::VectorXd q_last_, r_, coupling_, best_q_, rotation_;
  std::vector<int> diagonal_;  // per equation: the slot of K_ii in K's values
  bool kept_ = false;          // kept_K_ and kept_r_ are the last step's start (keep)
  std::vector<double> kept_K_;
  Eigen::VectorXd kept_r_;
};

}  // namespace

namespace {

// Increment targets: the schedule's breakpoints, or `steps` equal increments of λ.
std::vector<double> breakpoints(const SolverKnobs& knobs) {
  if (!knobs.schedule.empty()) {
    for (std::size_t k = 0; k < knobs.schedule.size(); ++k)
      if (!(knobs.schedule[k] > (k ? knobs.schedule[k - 1] : 0.0)) || knobs.schedule[k] > 1.0)
        throw core::UsageError("segment: the load schedule must increase within (0, 1]");
    std::vector<double> b = knobs.schedule;
    if (b.back() < 1.0) b.push_back(1.0);
    return b;
  }
  std::vector<double> b;
  const int n = std::max(1, knobs.steps);
  for (int k = 1; k <= n; ++k) b.push_back(static_cast<double>(k) / n);
  return b;
}

}  // namespace

namespace {

// One run of solve_static: Newton increments from λ = 0 to 1 with step cuts that grow back.
class StaticRun {
 public:
  StaticRun(const StaticProblem& p, const SolverKnobs& knobs)
      : p_(p), knobs_(knobs), m_(*p.mesh), d_(number_dofs(p)), angles_(p.constraints.size()),
        pool_(solver_threads(knobs)),
        assembler_(p, d_, gauss_order(m_, knobs.integration), knobs.integration == Integration::fbar, pool_),
        states_(initial_states(p, assembler_.points_per_element())), scratch_(states_.committed.size()),
        linear_(p.pressure_MPa == 0.0 && p.laws[0]->symmetric_tangent() && p.laws[1]->symmetric_tangent() &&
                symmetric_tangent(knobs.integration) && (!p.following_force.at || p.following_force.symmetric)),
        pattern_(linear_.symmetric() || knobs.krylov_iterations > 0 ? ordered_pattern(m_, d_) : build_pattern(m_, d_)), nn_(m_.node_count()), q_(Eigen::VectorXd::Zero(2 * nn_)),
        newton_(assembler_, pattern_, linear_, d_, knobs, q_), values_(p.constraints.size()) {
    assembler_.set_offsets(&states_.offset);
    out_.equations = d_.equations;
    if (knobs.inertia && p.density_t_mm3 > 0.0 && p.time_s) {  // dynamics hook (SolverKnobs::inertia)
      inertia_ = std::make_unique<detail::BackwardEulerInertia>(detail::lumped_masses(m_, p.density_t_mm3), p.frame_motion);
      assembler_.set_inertia(inertia_.get(), &newton_.diagonal());
    }
    out_.threads = pool_.threads();
  }

  StaticSolution run() {
    const std::vector<double> targets = breakpoints(knobs_);
    std::size_t next = 0;
    while (next < targets.size()) {
      const double target = std::min(targets[next], lambda_ + max_step_);
      if (increment(target)) {
        if (target >= targets[next]) ++next;
      } else if (++cuts_in_row_ > knobs_.max_cuts) {
        fail(out_.increments + 1, target, last_.bad_element, last_.residual, last_.iterations);
      } else {
        max_step_ = 0.5 * (target - lambda_);
        out_.cuts++;
      }
    }
    // After the swap, `trial` holds the states before the last increment.
    snapshot(1.0, states_.trial, last_dt_, out_);
    out_.pattern_analyses = linear_.analyses();
    out_.krylov_iterations = linear_.krylov_iterations();
    out_.krylov_fallbacks = linear_.krylov_fallbacks();
    out_.symmetric_solver = linear_.symmetric();
    out_.state = states_.committed;
    out_.state_offset = states_.offset;
    return out_;
  }

 private:
  double time_at(double lambda) const { return p_.time_s ? p_.time_s(lambda) : 0.0; }

  // q with the prescribed components at λ.
  Eigen::VectorXd prescribed_at(double lambda) {
    Eigen::VectorXd qp = q_;
    p_.prescribe(lambda, values_);
    for (std::size_t c = 0; c < p_.constraints.size(); ++c)
      for (int k = 0; k < 2; ++k)
        if (p_.constraints[c].fixed[k]) qp(2 * p_.constraints[c].node + k) = values_[c][k];
    return qp;
  }

  [[noreturn]] void fail(int increment, double lambda, int element, double residual, int iterations) {
    std::ostringstream msg;
    msg << "segment: Newton failed in load increment " << increment << " (lambda " << lambda;
    if (p_.time_s) msg << ", t " << time_at(lambda) << " s";
    msg << ")";
    if (element >= 0) msg << ", element " << element << " inverted or with a non-finite stress";
    msg << ", free residual " << residual << " N/mm after " << iterations << " iterations and "
        << knobs_.max_cuts << " step cuts";
    // Where: on the complete level a residual stuck near one node with no inverted element is a fold
    // of the load path there (docs/segment.md "Cost", "Diagnosis at the failing state");
    // `diagnose_failure` says which.
    if (const int n = newton_.worst_node(); n >= 0)
      msg << "; largest residual at node " << n << " (reference x " << m_.X[n].x() << ", y " << m_.X[n].y()
          << " mm)";
    if (knobs_.diagnose_failure) msg << diagnose(lambda);
    throw core::NumericalError(msg.str());
  }

  // The failure diagnosis at the increment's start (the last converged q with the prescribed motion
  // at λ) and at its best iterate, both on the step from the committed states.
  std::string diagnose(double lambda) {
    assembler_.set_step(states_.committed.data(), scratch_.data(), time_at(lambda) - time_at(lambda_));
    detail::DiagnosisProblem p;
    p.mesh = &m_, p.eq = &d_.eq, p.basis = &d_.R;
    p.residual = [&](const Eigen::VectorXd& q) {
      Eigen::VectorXd r;
      return assembler_.run(q, lambda, nullptr, r, nullptr, nullptr) >= 0 ? Eigen::VectorXd() : r;
    };
    p.tangent = [&](const Eigen::VectorXd& q) {
      Eigen::VectorXd r;
      assembler_.run(q, lambda, nullptr, r, &pattern_, nullptr);
      return pattern_.K;
    };
    p.element = [&](const Eigen::VectorXd& q, int e, detail::ElementVector& f, detail::ElementMatrix* K,
                    std::vector<detail::ElementState>* states) { return assembler_.element_at(q, e, f, K, states); };
    p.point = [&](int e, int g, const Eigen::Matrix2d& F, bool tangent) {
      const PlaneStrainLaw& law = assembler_.law_of(e);
      const detail::ElementStep step = assembler_.step_of(e);
      const std::size_t at = static_cast<std::size_t>(g) * law.state_size();
      return law.respond(F, {step.state_n + at, step.state_next + at, step.dt_s, step.temperature_C, tangent});
    };
    std::string text = detail::diagnose(p, prescribed_at(lambda), "increment start");
    if (newton_.best_iterate().size() == q_.size()) text += detail::diagnose(p, newton_.best_iterate(), "best iterate");
    return text;
  }

  // Stresses, displacements and reactions at the converged q (states from `from` over dt).
  void snapshot(double lambda, const std::vector<double>& from, double dt, StaticSolution& s) {
    assembler_.set_step(from.data(), scratch_.data(), dt);
    const int bad = assembler_.run(q_, lambda, nullptr, r_, nullptr, nullptr, &s.points);
    if (bad >= 0) fail(out_.increments, lambda, bad, out_.final_residual, 0);
    s.u_mm.resize(nn_);
    s.reaction_N_mm.assign(nn_, Eigen::Vector2d::Zero());
    for (int a = 0; a < nn_; ++a) {
      s.u_mm[a] = assembler_.u_of(q_, a);
      Eigen::Vector2d rl = r_.segment<2>(2 * a);
      for (int k = 0; k < 2; ++k)
        if (d_.eq[2 * a + k] >= 0) rl(k) = 0.0;
      s.reaction_N_mm[a] = d_.R[a] * rl;
    }
    s.inertia_N_mm = assembler_.inertia_forces(q_);
    s.following_N_mm = assembler_.following_forces(q_);
  }

  // Turn the constrained bases to λ = target, keeping the displacements.
  void rotate_bases(double target) {
    if (!p_.rotate) return;
    p_.rotate(target, angles_);
    for (std::size_t c = 0; c < p_.constraints.size(); ++c) {
      const int n = p_.constraints[c].node;
      const Eigen::Vector2d u = d_.R[n] * q_.segment<2>(2 * n);
      d_.R[n] << std::cos(angles_[c]), -std::sin(angles_[c]), std::sin(angles_[c]), std::cos(angles_[c]);
      q_.segment<2>(2 * n) = d_.R[n].transpose() * u;
    }
  }

  // Per free dof, (Q(θ) − I − θJ)(x − c) of its node's frame turn to λ = target (local components,
  // bases already turned), x the converged position: what the linear predictor leaves out of a
  // finite rotation.
  Eigen::VectorXd rotation_terms(double target) {
    p_.frame_turn(lambda_, target, turns_);
    Eigen::VectorXd extra = Eigen::VectorXd::Zero(2 * nn_);
    for (int a = 0; a < nn_; ++a) {
      const double th = turns_[a].angle_rad;
      const Eigen::Vector2d r = m_.X[a] + assembler_.u_of(q_, a) - turns_[a].centre_mm;
      const Eigen::Vector2d second_order = (std::cos(th) - 1.0) * r + (std::sin(th) - th) * Eigen::Vector2d(-r.y(), r.x());
      const Eigen::Vector2d local = d_.R[a].transpose() * second_order;
      for (int k = 0; k < 2; ++k)
        if (d_.eq[2 * a + k] >= 0) extra(2 * a + k) = local(k);
    }
    return extra;
  }

  // An attempt's work, added to the run's.
  void tally(const NewtonOutcome& attempt) {
    out_.newton_iterations += attempt.iterations;
    out_.factorizations += attempt.factorizations;
    out_.assemblies += attempt.assemblies;
  }

  // One increment to `target`: true (states committed) when Newton converged, else q restored.
  bool increment(double target) {
    rotate_bases(target);
    const Eigen::VectorXd q_saved = q_;
    const double dt = time_at(target) - time_at(lambda_);
    assembler_.set_step(states_.committed.data(), states_.trial.data(), dt);
    begin_inertia(target, dt);
    // Start: the free dofs extrapolated from the last increment (capped at its size, the history
    // turns at transitions); or, first and after a cut, the linear predictor K_fp·Δq_p on a fresh
    // tangent.
    Eigen::VectorXd q_start = prescribed_at(target);
    const bool extrapolate = (knobs_.extrapolate_start || (knobs_.reuse_tangent && have_factor_)) &&
                             cuts_in_row_ == 0 && velocity_.size() == q_.size();
    if (extrapolate) {
      const double ratio = std::min(1.0, (target - lambda_) / last_dlambda_);
      for (int i = 0; i < 2 * nn_; ++i)
        if (d_.eq[i] >= 0) q_start(i) += ratio * velocity_(i);
    }
    const bool rotated = knobs_.rotated_predictor && p_.frame_turn && !extrapolate;
    Eigen::VectorXd rotation = rotated ? rotation_terms(target) : Eigen::VectorXd();
    // Without terms this small the retake starts where this try did, to within Newton's first
    // correction: measured, such retakes never converged where the try had not (docs/segment.md
    // §Cost, "Retakes that cannot help").
    const bool retake = rotated && rotation.norm() > kRetakeRotation_mm;
    newton_.set_rotation(std::move(rotation));
    last_ = newton_.solve(target, q_start, extrapolate);
    if (retake && !last_.converged) {  // retaken on the plain linear predictor before a cut
      tally(last_);
      q_ = q_saved;
      newton_.set_rotation(Eigen::VectorXd());
      last_ = newton_.solve(target, q_start, false);
    }
    tally(last_);
    have_factor_ = have_factor_ || last_.factorizations > 0;
    if (!last_.converged) {
      q_ = q_saved;
      return false;
    }
    if (p_.on_increment) {
      StaticSolution view;
      snapshot(target, states_.committed, dt, view);
      view.increments = out_.increments + 1;
      p_.on_increment(target, view);
    }
    states_.committed.swap(states_.trial);  // the last assembly was at the converged q
    assembler_.commit_following(q_);        // prepared at target by that assembly
    velocity_ = q_ - q_saved;
    last_dt_ = dt;
    last_dlambda_ = target - lambda_;
    lambda_ = target;
    out_.increments++;
    out_.final_residual = last_.residual;
    cuts_in_row_ = 0;
    if (knobs_.growth_iterations <= 0 || last_.iterations <= knobs_.growth_iterations)
      max_step_ = std::min(2.0, 2.0 * max_step_);  // a cut step grows back after an easy success
    inertia_pending_ = true;
    return true;
  }

  // The inertia's history takes the last converged increment's motion when the next one begins (so
  // the final snapshot still sees the last increment's step), then the step to `target`.
  void begin_inertia(double target, double dt) {
    if (!inertia_) return;
    if (inertia_pending_) {
      std::vector<Eigen::Vector2d> u(nn_);
      for (int a = 0; a < nn_; ++a) u[a] = assembler_.u_of(q_, a);
      inertia_->commit(u);
      inertia_pending_ = false;
    }
    inertia_->begin(target, dt);
  }

  const StaticProblem& p_;
  const SolverKnobs& knobs_;
  const Mesh& m_;
  Dofs d_;
  std::vector<double> angles_;
  detail::WorkerPool pool_;
  Assembler assembler_;
  StateBlock states_;
  std::vector<double> scratch_;
  LinearSolver linear_;
  Pattern pattern_;
  const int nn_;
  Eigen::VectorXd q_, r_;
  Newton newton_;
  std::vector<std::array<double, 2>> values_;
  StaticSolution out_;
  NewtonOutcome last_;
  double lambda_ = 0.0, max_step_ = 2.0, last_dt_ = 0.0, last_dlambda_ = 0.0;
  int cuts_in_row_ = 0;
  bool have_factor_ = false;
  Eigen::VectorXd velocity_;  // Δq of the last converged increment (local components)
  std::vector<StaticProblem::FrameTurn> turns_;
  std::unique_ptr<detail::BackwardEulerInertia> inertia_;  // SolverKnobs::inertia
  bool inertia_pending_ = false;
};

}  // namespace

int solver_threads(const SolverKnobs& knobs) {
  if (knobs.threads > 0) return knobs.threads;
  return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 2u));
}

StaticSolution solve_static(const StaticProblem& p, const SolverKnobs& knobs) {
  if (!p.mesh || !p.laws[0] || !p.laws[1] || !p.prescribe)
    throw core::UsageError("solve_static: mesh, both laws and the prescribed displacements are required");
  if (knobs.threads < 0) throw core::UsageError("solve_static: threads must be >= 1, or 0 for the default");
  return StaticRun(p, knobs).run();
}

SectionForce section_force(const StaticProblem& p, const StaticSolution& s, double x_cut,
                           const Eigen::Vector2d& about, Integration integration) {
  const Mesh& m = *p.mesh;
  const auto rule = detail::gauss_rule(gauss_order(m, integration));
  const int npe = m.nodes_per_element;
  const double tol = 1e-9 * (1.0 + m.half_length_mm);
  std::vector<Eigen::Vector2d> X(npe), u(npe);
  ElementVector f;
  SectionForce out;
  for (int e = 0; e < m.element_count(); ++e) {
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (int a = 0; a < 4; ++a) centroid += 0.25 * m.X[m.elements[e][a]];
    if (centroid.x() >= x_cut) continue;
    bool touches = false;
    for (int a = 0; a < npe; ++a) {
      X[a] = m.X[m.elements[e][a]];
      u[a] = s.u_mm[m.elements[e][a]];
      touches = touches || std::abs(X[a].x() - x_cut) < tol;
    }
    if (!touches) continue;
    std::vector<Eigen::Matrix2d> piola;
    for (const IntegrationPointStress& q : s.points[e]) piola.push_back(q.piola_MPa);
    detail::internal_force(X, rule, piola, f);
    for (int a = 0; a < npe; ++a) {
      if (std::abs(X[a].x() - x_cut) >= tol) continue;
      const Eigen::Vector2d fa = f.segment<2>(2 * a), x = X[a] + u[a] - about;
      out.force_N_mm += fa;
      out.moment_N += x.y() * fa.x() - x.x() * fa.y();
    }
  }
  return out;
}

namespace {

// P's isoparametric coordinates in element e by Newton on its reference map; false if P is not in it.
bool inverse_map(const Mesh& m, int e, const Eigen::Vector2d& P, Eigen::Vector2d& xi) {
  const int npe = m.nodes_per_element;
  double N[8], dxi[8], deta[8];
  Eigen::Vector2d lo = m.X[m.elements[e][0]], hi = lo;
  for (int a = 0; a < npe; ++a) lo = lo.cwiseMin(m.X[m.elements[e][a]]), hi = hi.cwiseMax(m.X[m.elements[e][a]]);
  const double pad = 1e-9 * (1.0 + (hi - lo).norm());
  if ((P.array() < lo.array() - pad).any() || (P.array() > hi.array() + pad).any()) return false;
  xi.setZero();
  for (int it = 0; it < 30; ++it) {
    detail::shape(npe, xi.x(), xi.y(), N, dxi, deta);
    Eigen::Vector2d x = Eigen::Vector2d::Zero();
    Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
    for (int a = 0; a < npe; ++a) {
      const Eigen::Vector2d& Xa = m.X[m.elements[e][a]];
      x += N[a] * Xa;
      J.col(0) += dxi[a] * Xa, J.col(1) += deta[a] * Xa;
    }
    xi += J.inverse() * (P - x);
  }
  return xi.allFinite() && xi.cwiseAbs().maxCoeff() <= 1.0 + 1e-7;
}

void add_scaled(IntegrationPointStress& out, const IntegrationPointStress& q, double w) {
  out.cauchy_MPa += w * q.cauchy_MPa, out.sigma33_MPa += w * q.sigma33_MPa;
  out.piola_MPa += w * q.piola_MPa, out.F += w * q.F;
}

// One element's integration-point values at `at` by the Lagrange polynomials through the Gauss
// abscissae g.
IntegrationPointStress interpolate_in(const StaticSolution& s, const ElementPoint& at, const std::vector<double>& g,
                                      const Eigen::Vector2d& X) {
  const int n = static_cast<int>(g.size());
  auto lagrange = [&](int i, double t) {
    double v = 1.0;
    for (int j = 0; j < n; ++j)
      if (j != i) v *= (t - g[j]) / (g[i] - g[j]);
    return v;
  };
  IntegrationPointStress out{X, Eigen::Matrix2d::Zero(), 0.0, Eigen::Matrix2d::Zero(), Eigen::Matrix2d::Zero()};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      add_scaled(out, s.points[at.element][j * n + i], lagrange(i, at.xi.x()) * lagrange(j, at.xi.y()));
  return out;
}

}  // namespace

PointLocation locate(const Mesh& m, const Eigen::Vector2d& P) {
  PointLocation out;
  Eigen::Vector2d xi;
  for (int e = 0; e < m.element_count(); ++e) {
    if (!inverse_map(m, e, P, xi)) continue;
    if (out.element < 0) out.element = e, out.xi = xi;
    else if (m.roles[e] == m.roles[out.element]) out.shared.push_back({e, xi});
  }
  if (out.element >= 0) return out;
  std::ostringstream msg;
  msg << "point (" << P.x() << ", " << P.y() << ") mm is outside the segment mesh";
  throw core::InputError(msg.str());
}

IntegrationPointStress interpolate(const StaticSolution& s, const PointLocation& at, int n, const Eigen::Vector2d& X) {
  const std::vector<double> g = detail::gauss_abscissae(n);
  IntegrationPointStress out = interpolate_in(s, {at.element, at.xi}, g, X);
  for (const ElementPoint& other : at.shared) add_scaled(out, interpolate_in(s, other, g, X), 1.0);
  const double w = 1.0 / (1.0 + static_cast<double>(at.shared.size()));
  out.cauchy_MPa *= w, out.sigma33_MPa *= w, out.piola_MPa *= w, out.F *= w;
  return out;
}

Eigen::Matrix2d stress_at(const Mesh& m, const StaticSolution& s, const Eigen::Vector2d& P,
                          Integration integration, double* sigma33) {
  const IntegrationPointStress q = interpolate(s, locate(m, P), gauss_order(m, integration), P);
  if (sigma33) *sigma33 = q.sigma33_MPa;
  return q.cauchy_MPa;
}

}  // namespace fitlib::segment
