// The segment's element loop (assembler.hpp).
#include "assembler.hpp"

#include <algorithm>

namespace fitlib::segment::detail {

// Adds an element's (or edge's) local force and tangent: free-free entries into K's slots,
// free-prescribed ones times the prescribed step into coupling (the predictor).
template <typename Nodes>
void Assembler::scatter(const Nodes& nodes, const ElementVector& f, const ElementMatrix* Ke, const Eigen::VectorXd* dq_p,
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

// One element's response at q, as run() computes it (the failure diagnosis).
bool Assembler::element_at(const Eigen::VectorXd& q, int e, ElementVector& f, ElementMatrix* Ke,
                std::vector<ElementState>* states) const {
  const Mesh& m = *p_.mesh;
  std::vector<Eigen::Vector2d> X, u;
  for (int a = 0; a < m.nodes_per_element; ++a) X.push_back(m.X[m.elements[e][a]]), u.push_back(u_of(q, m.elements[e][a]));
  const bool ok = element_response(X, u, law_of(e), rule_, step_of(e), f, Ke, states, f_bar_);
  if (ok) add_following(e, X, u, f, Ke);
  return ok;
}

// Residual (local components, all dofs) and, if asked, the free-free tangent into the pattern's
// values and K_fp·dq_p into coupling. Returns the failing element, or −1. The elements' responses
// are computed on the pool into their buffers, then added in element order up to the first
// failing one, exactly as a serial loop would (bit-identical whatever the thread count).
int Assembler::run(const Eigen::VectorXd& q, double lambda, const Eigen::VectorXd* dq_p, Eigen::VectorXd& r,
        Pattern* K, Eigen::VectorXd* coupling,
        std::vector<std::vector<IntegrationPointStress>>* states) const {
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
  add_pressure(q, lambda, dq_p, r, K, coupling);
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
std::vector<Eigen::Vector2d> Assembler::following_forces(const Eigen::VectorXd& q) const {
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
void Assembler::commit_following(const Eigen::VectorXd& q) const {
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
std::vector<Eigen::Vector2d> Assembler::inertia_forces(const Eigen::VectorXd& q) const {
  std::vector<Eigen::Vector2d> f;
  for (int n = 0; inertia_ && n < p_.mesh->node_count(); ++n)
    f.push_back(moves(n) ? inertia_->force(n, u_of(q, n)) : Eigen::Vector2d::Zero());
  return f;
}

// Element e's response at q into a buffer (runs on any of the pool's threads: writes only that
// buffer and element e's trial states).
void Assembler::add_pressure(const Eigen::VectorXd& q, double lambda, const Eigen::VectorXd* dq_p,
                             Eigen::VectorXd& r, Pattern* K, Eigen::VectorXd* coupling) const {
  const double pressure = lambda * p_.pressure_MPa;
  if (pressure == 0.0) return;
  const Mesh& m = *p_.mesh;
  for (std::size_t k = 0; k < m.bottom_edges.size(); ++k) {
    const std::vector<int> en = edge_nodes(m.bottom_edges[k]);
    std::vector<Eigen::Vector2d> x;
    for (int a : en) x.push_back(m.X[a] + u_of(q, a));
    ElementVector f;
    ElementMatrix Ke;
    pressure_load(x, pressure, f, Ke);
    f = -f;
    Ke = -Ke;
    to_local(en.data(), static_cast<int>(en.size()), f, K ? &Ke : nullptr);
    scatter(en.data(), f, K ? &Ke : nullptr, dq_p, r, K, K ? &K->edge_slots[k] : nullptr, coupling);
  }
}

void Assembler::respond(const Eigen::VectorXd& q, int e, bool tangent, bool states, ElementBuffer& b) const {
  const Mesh& m = *p_.mesh;
  const int npe = m.nodes_per_element;
  const int* nodes = m.elements[e].data();
  b.X.resize(npe), b.u.resize(npe);
  for (int a = 0; a < npe; ++a) b.X[a] = m.X[nodes[a]], b.u[a] = u_of(q, nodes[a]);
  b.ok = element_response(b.X, b.u, law_of(e), rule_, step_of(e), b.f, tangent ? &b.K : nullptr,
                                  states ? &b.states : nullptr, f_bar_);
  if (b.ok) add_following(e, b.X, b.u, b.f, tangent ? &b.K : nullptr);
  if (b.ok) to_local(nodes, npe, b.f, tangent ? &b.K : nullptr);
}

// f and K from global components to the nodes' local bases (Rᵀf, R_aᵀ K_ab R_b); a node without
// a constraint has R = I and is left as it is.
void Assembler::to_local(const int* nodes, int n, ElementVector& f, ElementMatrix* K) const {
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
void Assembler::point_weights() {
  const Mesh& m = *p_.mesh;
  const int npe = m.nodes_per_element;
  double N[8], dxi[8], deta[8];
  for (const auto& g : rule_) {
    shape(npe, g.xi, g.eta, N, dxi, deta);
    shape_.insert(shape_.end(), N, N + npe);
  }
  for (int e = 0; e < m.element_count(); ++e)
    for (const auto& g : rule_) volume_.push_back(reference_jacobian(m, e, g.xi, g.eta) * g.weight);
}

// StaticProblem::following_force at element e's points (global components): −∫ N_a b dV into the
// force, −∫ N_a N_b ∂b/∂x dV into the tangent.
void Assembler::add_following(int e, const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& u,
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
void Assembler::add_body_forces(double lambda, Eigen::VectorXd& r) const {
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

// m·a of every node with a free component into the residual (a cord-line node follows its frame
// exactly), m/Δt² onto the diagonal of its free equations (the mass is isotropic, so a node's
// rotated basis leaves it diagonal and uncoupled from the prescribed components).
void Assembler::add_inertia(const Eigen::VectorXd& q, Eigen::VectorXd& r, Pattern* K) const {
  for (int n = 0; n < p_.mesh->node_count(); ++n) {
    if (!moves(n)) continue;
    r.segment<2>(2 * n) += d_.R[n].transpose() * inertia_->force(n, u_of(q, n));
    for (int k = 0; K && k < 2; ++k)
      if (d_.eq[2 * n + k] >= 0) K->K.valuePtr()[(*diagonal_)[d_.eq[2 * n + k]]] += inertia_->stiffness(n);
  }
}

}  // namespace fitlib::segment::detail
