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

Assembler::Assembler(const StaticProblem& p, const Dofs& d, int order, bool f_bar, WorkerPool& pool,
                     std::vector<Load*> loads)
    : p_(p), d_(d), rule_(gauss_rule(order)), f_bar_(f_bar), pool_(pool),
      buffers_(pool.threads() > 1 ? p.mesh->element_count() : 1), loads_(std::move(loads)) {
  for (Load* load : loads_)
    if (load->acts_at_points()) point_loads_.push_back(load);
  point_weights();
}

// One assembly's LoadAssembly: a load's contributions in global components, turned into the
// nodes' local bases and added to the residual and the tangent's slots.
class Assembler::Pass final : public LoadAssembly {
 public:
  Pass(const Assembler& a, const Eigen::VectorXd& q, double lambda, const Eigen::VectorXd* dq_p, Eigen::VectorXd& r,
       Pattern* K, Eigen::VectorXd* coupling)
      : a_(a), q_(q), lambda_(lambda), dq_p_(dq_p), r_(r), K_(K), coupling_(coupling) {}
  double lambda() const override { return lambda_; }
  bool tangent() const override { return K_ != nullptr; }
  int node_count() const override { return a_.p_.mesh->node_count(); }
  Eigen::Vector2d u(int node) const override { return a_.u_of(q_, node); }
  bool moves(int node) const override { return a_.moves(node); }
  void add_element_forces(const std::vector<Eigen::Vector2d>& b) override { a_.add_body_forces(b, r_); }
  void add_bottom_edge(int edge, LoadVector f, LoadMatrix K) override {
    const std::vector<int> en = edge_nodes(a_.p_.mesh->bottom_edges[edge]);
    a_.to_local(en.data(), static_cast<int>(en.size()), f, K_ ? &K : nullptr);
    a_.scatter(en.data(), f, K_ ? &K : nullptr, dq_p_, r_, K_, K_ ? &K_->edge_slots[edge] : nullptr, coupling_);
  }
  void add_node_force(int node, const Eigen::Vector2d& f) override {
    r_.segment<2>(2 * node) += a_.d_.R[node].transpose() * f;
  }
  void add_node_stiffness(int node, double k) override {
    for (int c = 0; K_ && c < 2; ++c)
      if (a_.d_.eq[2 * node + c] >= 0) K_->K.valuePtr()[(*a_.diagonal_)[a_.d_.eq[2 * node + c]]] += k;
  }

 private:
  const Assembler& a_;
  const Eigen::VectorXd& q_;
  double lambda_;
  const Eigen::VectorXd* dq_p_;
  Eigen::VectorXd& r_;
  Pattern* K_;
  Eigen::VectorXd* coupling_;
};

// One element's response at q, as run() computes it (the failure diagnosis).
bool Assembler::element_at(const Eigen::VectorXd& q, int e, ElementVector& f, ElementMatrix* Ke,
                std::vector<ElementState>* states) const {
  const Mesh& m = *p_.mesh;
  std::vector<Eigen::Vector2d> X, u;
  for (int a = 0; a < m.nodes_per_element; ++a) X.push_back(m.X[m.elements[e][a]]), u.push_back(u_of(q, m.elements[e][a]));
  const bool ok = element_response(X, u, law_of(e), rule_, step_of(e), f, Ke, states, f_bar_, nullptr,
                                   reference_.data() + e * rule_.size());
  if (ok) add_point_loads(e, X, u, f, Ke);
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
  std::vector<std::vector<IntegrationPointStress>>& points = states ? *states : last_points_;
  points.resize(m.element_count());
  for (auto& element : points) element.clear();
  if (lambda != prepared_at_) {  // dead loads are functions of λ: evaluated once per λ, not per iteration
    for (Load* load : loads_) load->prepare(lambda);
    prepared_at_ = lambda;
  }
  // One thread: each element computed into one buffer and added at once (the same operations in
  // the same order as with the team, without a pass over all buffers: cache).
  const bool team = pool_.threads() > 1;
  if (team) pool_.for_each(m.element_count(), [&](int e) { respond(q, e, K != nullptr, buffers_[e]); });
  for (int e = 0; e < m.element_count(); ++e) {
    const ElementBuffer& b = team ? buffers_[e] : buffers_[0];
    if (!team) respond(q, e, K != nullptr, buffers_[0]);
    if (!b.ok) return e;
    scatter(m.elements[e], b.f, K ? &b.K : nullptr, dq_p, r, K, K ? &K->element_slots[e] : nullptr, coupling);
    for (const auto& s : b.states) points[e].push_back({s.X_mm, s.cauchy_MPa, s.sigma33_MPa, s.piola_MPa, s.F});
  }
  Pass pass(*this, q, lambda, dq_p, r, K, coupling);
  for (const Load* load : loads_) load->add(pass);
  return -1;
}

// Per element, the point loads' ∫ b dV at q (global; empty without one), at the λ of the last
// assembly.
std::vector<Eigen::Vector2d> Assembler::point_load_forces(const Eigen::VectorXd& q) const {
  const Mesh& m = *p_.mesh;
  std::vector<Eigen::Vector2d> out;
  if (point_loads_.empty()) return out;
  const int npe = m.nodes_per_element;
  std::vector<Eigen::Vector2d> X(npe), u(npe);
  ElementVector f;
  for (int e = 0; e < m.element_count(); ++e) {
    for (int a = 0; a < npe; ++a) X[a] = m.X[m.elements[e][a]], u[a] = u_of(q, m.elements[e][a]);
    f.setZero(2 * npe);
    add_point_loads(e, X, u, f, nullptr);
    Eigen::Vector2d total = Eigen::Vector2d::Zero();
    for (int a = 0; a < npe; ++a) total -= f.segment<2>(2 * a);
    out.push_back(total);
  }
  return out;
}

std::vector<Eigen::Vector2d> Assembler::displacements(const Eigen::VectorXd& q) const {
  std::vector<Eigen::Vector2d> u(p_.mesh->node_count());
  for (int a = 0; a < p_.mesh->node_count(); ++a) u[a] = u_of(q, a);
  return u;
}

std::vector<Eigen::Vector2d> Assembler::point_positions(const Eigen::VectorXd& q) const {
  const Mesh& m = *p_.mesh;
  const int npe = m.nodes_per_element;
  std::vector<Eigen::Vector2d> out;
  for (int e = 0; e < m.element_count(); ++e)
    for (std::size_t g = 0; g < rule_.size(); ++g) {
      const double* N = shape_.data() + g * npe;
      Eigen::Vector2d x = Eigen::Vector2d::Zero();
      for (int a = 0; a < npe; ++a) x += N[a] * (m.X[m.elements[e][a]] + u_of(q, m.elements[e][a]));
      out.push_back(x);
    }
  return out;
}

void Assembler::begin(const Eigen::VectorXd& q, double lambda, double dt_s) const {
  const std::vector<Eigen::Vector2d> u = displacements(q);
  for (Load* load : loads_) load->begin({lambda, dt_s, &u});
}

void Assembler::commit(const Eigen::VectorXd& q, double lambda) const {
  const std::vector<Eigen::Vector2d> u = displacements(q), x = point_positions(q);
  for (Load* load : loads_) load->commit({lambda, &u, &x, static_cast<int>(rule_.size())});
}

// Element e's response at q into a buffer (runs on any of the pool's threads: writes only that
// buffer and element e's trial states).
void Assembler::respond(const Eigen::VectorXd& q, int e, bool tangent, ElementBuffer& b) const {
  const Mesh& m = *p_.mesh;
  const int npe = m.nodes_per_element;
  const int* nodes = m.elements[e].data();
  b.X.resize(npe), b.u.resize(npe);
  for (int a = 0; a < npe; ++a) b.X[a] = m.X[nodes[a]], b.u[a] = u_of(q, nodes[a]);
  PressureMemory memory{last_F_.data() + e * rule_.size(), follows_step_};
  b.ok = element_response(b.X, b.u, law_of(e), rule_, step_of(e), b.f, tangent ? &b.K : nullptr,
                          &b.states, f_bar_, tangent && !last_F_.empty() ? &memory : nullptr,
                          reference_.data() + e * rule_.size());
  if (b.ok) add_point_loads(e, b.X, b.u, b.f, tangent ? &b.K : nullptr);
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
// forces' and the point loads' weights; the shape functions are the same in every element).
void Assembler::point_weights() {
  const Mesh& m = *p_.mesh;
  const int npe = m.nodes_per_element;
  double N[8], dxi[8], deta[8];
  for (const auto& g : rule_) {
    shape(npe, g.xi, g.eta, N, dxi, deta);
    shape_.insert(shape_.end(), N, N + npe);
  }
  std::vector<Eigen::Vector2d> X(npe);
  for (int e = 0; e < m.element_count(); ++e) {
    for (int a = 0; a < npe; ++a) X[a] = m.X[m.elements[e][a]];
    const std::vector<ReferencePoint> points = reference_points(X, rule_);
    reference_.insert(reference_.end(), points.begin(), points.end());
    for (std::size_t g = 0; g < rule_.size(); ++g) volume_.push_back(reference_jacobian(m, e, rule_[g].xi, rule_[g].eta) * rule_[g].weight);
  }
}

// The point loads at element e's points (global components): −∫ N_a b dV into the force,
// −∫ N_a N_b ∂b/∂x dV into the tangent.
void Assembler::add_point_loads(int e, const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& u,
                                ElementVector& f, ElementMatrix* K) const {
  if (point_loads_.empty()) return;
  const int npe = p_.mesh->nodes_per_element;
  Eigen::Vector2d b;
  Eigen::Matrix2d db;
  for (std::size_t g = 0; g < rule_.size(); ++g) {
    const double* N = shape_.data() + g * npe;
    Eigen::Vector2d x = Eigen::Vector2d::Zero();
    for (int a = 0; a < npe; ++a) x += N[a] * (X[a] + u[a]);
    for (const Load* load : point_loads_) {
      if (!load->at_point(e, static_cast<int>(g), x, b, db)) continue;
      const double dV = volume_[e * rule_.size() + g];
      for (int a = 0; a < npe; ++a) {
        f.segment<2>(2 * a) -= N[a] * dV * b;
        for (int c = 0; K && c < npe; ++c) K->block<2, 2>(2 * a, 2 * c) -= N[a] * N[c] * dV * db;
      }
    }
  }
}

// Dead body forces b (N/mm³ of reference volume, per element) as consistent nodal loads
// −∫ N_a b dV (the residual is internal minus external force).
void Assembler::add_body_forces(const std::vector<Eigen::Vector2d>& body, Eigen::VectorXd& r) const {
  const Mesh& m = *p_.mesh;
  const int npe = m.nodes_per_element;
  for (int e = 0; e < m.element_count(); ++e) {
    if (body[e].isZero(0.0)) continue;
    for (std::size_t g = 0; g < rule_.size(); ++g)
      for (int a = 0; a < npe; ++a) {
        const int n = m.elements[e][a];
        r.segment<2>(2 * n) -= d_.R[n].transpose() * ((shape_[g * npe + a] * volume_[e * rule_.size() + g]) * body[e]);
      }
  }
}

}  // namespace fitlib::segment::detail
