#include "fitlib/segment/solver.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include "element.hpp"
#include "fitlib/core/error.hpp"

namespace fitlib::segment {

int gauss_order(const Mesh& mesh, Integration integration) {
  return (mesh.nodes_per_element == 8 && integration == Integration::full) ? 3 : 2;
}

namespace {
using detail::ElementMatrix;
using detail::ElementVector;
using SparseMatrix = Eigen::SparseMatrix<double>;

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

// Sparse direct solver: LDLᵀ for the symmetric tangent, LU when a follower pressure makes it
// unsymmetric; the sparsity pattern is analysed once.
class LinearSolver {
 public:
  explicit LinearSolver(bool symmetric) : symmetric_(symmetric) {}
  bool factorize(const SparseMatrix& K) {
    if (symmetric_) {
      if (!analysed_) ldlt_.analyzePattern(K);
      ldlt_.factorize(K);
      analysed_ = true;
      return ldlt_.info() == Eigen::Success;
    }
    if (!analysed_) lu_.analyzePattern(K);
    lu_.factorize(K);
    analysed_ = true;
    return lu_.info() == Eigen::Success;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) {
    if (symmetric_) return ldlt_.solve(b);
    return lu_.solve(b);
  }

 private:
  bool symmetric_, analysed_ = false;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  Eigen::SparseLU<SparseMatrix> lu_;
};

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

class Assembler {
 public:
  Assembler(const StaticProblem& p, const Dofs& d, int order)
      : p_(p), d_(d), rule_(detail::gauss_rule(order)) {}

  std::size_t points_per_element() const { return rule_.size(); }
  // The step the point states are updated over (state_n → state_next).
  void set_step(const double* state_n, double* state_next, double dt_s) {
    state_n_ = state_n, state_next_ = state_next, dt_s_ = dt_s;
  }
  void set_offsets(const std::vector<std::size_t>* offset) { offset_ = offset; }

  Eigen::Vector2d u_of(const Eigen::VectorXd& q, int node) const { return d_.R[node] * q.segment<2>(2 * node); }

  // Residual (local components, all dofs) and, if asked, the free-free tangent as triplets and
  // K_fp·dq_p into coupling. Returns the failing element, or −1.
  int run(const Eigen::VectorXd& q, double lambda, const Eigen::VectorXd* dq_p, Eigen::VectorXd& r,
          std::vector<Eigen::Triplet<double>>* K, Eigen::VectorXd* coupling,
          std::vector<std::vector<IntegrationPointStress>>* states = nullptr) const {
    const Mesh& m = *p_.mesh;
    r.setZero(2 * m.node_count());
    if (K) K->clear();
    if (coupling) coupling->setZero(d_.equations);
    if (states) states->assign(m.element_count(), {});
    const int npe = m.nodes_per_element;
    std::vector<Eigen::Vector2d> X(npe), u(npe);
    std::vector<int> nodes(npe);
    ElementVector f;
    ElementMatrix Ke;
    std::vector<detail::ElementState> gp;
    for (int e = 0; e < m.element_count(); ++e) {
      for (int a = 0; a < npe; ++a) {
        nodes[a] = m.elements[e][a];
        X[a] = m.X[nodes[a]];
        u[a] = u_of(q, nodes[a]);
      }
      const std::size_t at = (*offset_)[e];
      const detail::ElementStep step{state_n_ + at, state_next_ + at, dt_s_, p_.temperature_C};
      if (!detail::element_response(X, u, *p_.laws[static_cast<int>(m.roles[e])], rule_, step, f,
                                    K ? &Ke : nullptr, states ? &gp : nullptr))
        return e;
      scatter(nodes, f, K ? &Ke : nullptr, dq_p, r, K, coupling);
      if (states)
        for (const auto& s : gp) (*states)[e].push_back({s.X_mm, s.cauchy_MPa, s.sigma33_MPa, s.piola_MPa, s.F});
    }
    const double pressure = lambda * p_.pressure_MPa;
    if (pressure != 0.0)
      for (const Edge& edge : m.bottom_edges) {
        std::vector<int> en;
        std::vector<Eigen::Vector2d> x;
        for (int a : edge.nodes)
          if (a >= 0) en.push_back(a), x.push_back(m.X[a] + u_of(q, a));
        detail::pressure_load(x, pressure, f, Ke);
        f = -f;
        Ke = -Ke;
        scatter(en, f, K ? &Ke : nullptr, dq_p, r, K, coupling);
      }
    return -1;
  }

 private:
  void scatter(const std::vector<int>& nodes, const ElementVector& f, const ElementMatrix* Ke,
               const Eigen::VectorXd* dq_p, Eigen::VectorXd& r, std::vector<Eigen::Triplet<double>>* K,
               Eigen::VectorXd* coupling) const {
    const int n = static_cast<int>(nodes.size());
    for (int a = 0; a < n; ++a) r.segment<2>(2 * nodes[a]) += d_.R[nodes[a]].transpose() * f.segment<2>(2 * a);
    if (!Ke) return;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const Eigen::Matrix2d k = d_.R[nodes[a]].transpose() * Ke->block<2, 2>(2 * a, 2 * b) * d_.R[nodes[b]];
        for (int i = 0; i < 2; ++i) {
          const int row = d_.eq[2 * nodes[a] + i];
          if (row < 0) continue;
          for (int j = 0; j < 2; ++j) {
            const int col = d_.eq[2 * nodes[b] + j];
            if (col >= 0) K->emplace_back(row, col, k(i, j));
            else if (dq_p) (*coupling)(row) += k(i, j) * (*dq_p)(2 * nodes[b] + j);
          }
        }
      }
  }

  const StaticProblem& p_;
  const Dofs& d_;
  std::vector<detail::GaussPoint> rule_;
  const std::vector<std::size_t>* offset_ = nullptr;
  const double* state_n_ = nullptr;
  double* state_next_ = nullptr;
  double dt_s_ = 0.0;
};

double free_norm(const Eigen::VectorXd& r, const Dofs& d, bool free) {
  double s = 0.0;
  for (int i = 0; i < r.size(); ++i)
    if ((d.eq[i] >= 0) == free) s += r(i) * r(i);
  return std::sqrt(s);
}

}  // namespace

StaticSolution solve_static(const StaticProblem& p, const SolverKnobs& knobs) {
  if (!p.mesh || !p.laws[0] || !p.laws[1] || !p.prescribe)
    throw core::UsageError("solve_static: mesh, both laws and the prescribed displacements are required");
  const Mesh& m = *p.mesh;
  Dofs d = number_dofs(p);
  std::vector<double> angles(p.constraints.size());
  Assembler assembler(p, d, gauss_order(m, knobs.integration));
  StateBlock states = initial_states(p, assembler.points_per_element());
  assembler.set_offsets(&states.offset);
  auto time_at = [&](double lambda) { return p.time_s ? p.time_s(lambda) : 0.0; };
  LinearSolver linear(p.pressure_MPa == 0.0 && p.laws[0]->symmetric_tangent() && p.laws[1]->symmetric_tangent());
  const int nn = m.node_count();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(2 * nn), r, coupling;
  std::vector<std::array<double, 2>> values(p.constraints.size());
  std::vector<Eigen::Triplet<double>> triplets;
  SparseMatrix K(d.equations, d.equations);
  StaticSolution out;
  out.equations = d.equations;

  auto prescribed_at = [&](double lambda) {
    p.prescribe(lambda, values);
    Eigen::VectorXd qp = q;
    for (std::size_t c = 0; c < p.constraints.size(); ++c)
      for (int k = 0; k < 2; ++k)
        if (p.constraints[c].fixed[k]) qp(2 * p.constraints[c].node + k) = values[c][k];
    return qp;
  };
  auto fail = [&](int increment, double lambda, int element, double residual, int iterations) {
    std::ostringstream msg;
    msg << "segment: Newton failed in load increment " << increment << " (lambda " << lambda << ")";
    if (element >= 0) msg << ", element " << element << " inverted or with a non-finite stress";
    msg << ", free residual " << residual << " N/mm after " << iterations << " iterations and "
        << knobs.max_cuts << " step cuts";
    throw core::NumericalError(msg.str());
  };

  double lambda = 0.0, dlambda = 1.0 / std::max(1, knobs.steps);
  int cuts_in_row = 0;
  double last_dt = 0.0;
  while (lambda < 1.0 - 1e-14) {
    const double target = std::min(1.0, lambda + dlambda);
    if (p.rotate) {  // turn the constrained bases, keeping the displacements
      p.rotate(target, angles);
      for (std::size_t c = 0; c < p.constraints.size(); ++c) {
        const int n = p.constraints[c].node;
        const Eigen::Vector2d u = d.R[n] * q.segment<2>(2 * n);
        d.R[n] << std::cos(angles[c]), -std::sin(angles[c]), std::sin(angles[c]), std::cos(angles[c]);
        q.segment<2>(2 * n) = d.R[n].transpose() * u;
      }
    }
    const Eigen::VectorXd q_saved = q;
    assembler.set_step(states.committed.data(), states.trial.data(), time_at(target) - time_at(lambda));
    const Eigen::VectorXd q_new_p = prescribed_at(target);
    Eigen::VectorXd dq_p = q_new_p - q;  // nonzero only at prescribed dofs
    int bad = -1, it = 0;
    double res = std::numeric_limits<double>::infinity();
    bool converged = false;
    for (it = 0; it < knobs.max_iterations; ++it) {
      const bool predictor = it == 0;
      bad = assembler.run(q, target, predictor ? &dq_p : nullptr, r, &triplets, &coupling);
      if (bad >= 0) break;
      res = free_norm(r, d, true);
      if (!std::isfinite(res)) break;
      if (!predictor && res <= knobs.tolerance * (free_norm(r, d, false) + 1.0)) {
        converged = true;
        break;
      }
      K.setFromTriplets(triplets.begin(), triplets.end());
      if (!linear.factorize(K)) break;
      Eigen::VectorXd rhs(d.equations);
      for (int i = 0; i < 2 * nn; ++i)
        if (d.eq[i] >= 0) rhs(d.eq[i]) = -r(i);
      if (predictor) rhs -= coupling;
      const Eigen::VectorXd dq = linear.solve(rhs);
      if (!dq.allFinite()) break;
      // Backtracking line search on the free residual norm (the predictor step is taken whole).
      const Eigen::VectorXd q0 = predictor ? q_new_p : q;
      double alpha = 1.0, best = std::numeric_limits<double>::infinity(), best_alpha = 1.0;
      for (int ls = 0; ls < (predictor ? 1 : 5); ++ls, alpha *= 0.5) {
        Eigen::VectorXd trial = q0;
        for (int i = 0; i < 2 * nn; ++i)
          if (d.eq[i] >= 0) trial(i) += alpha * dq(d.eq[i]);
        Eigen::VectorXd rt;
        const double n_t = assembler.run(trial, target, nullptr, rt, nullptr, nullptr) >= 0
                               ? std::numeric_limits<double>::infinity()
                               : free_norm(rt, d, true);
        if (n_t < best) best = n_t, best_alpha = alpha;
        if (n_t < res) break;
      }
      for (int i = 0; i < 2 * nn; ++i)
        q(i) = q0(i) + (d.eq[i] >= 0 ? best_alpha * dq(d.eq[i]) : 0.0);
      out.newton_iterations++;
    }
    if (converged) {
      // The last assembly was at the converged q: trial holds its states.
      states.committed.swap(states.trial);
      last_dt = time_at(target) - time_at(lambda);
      lambda = target;
      out.increments++;
      out.final_residual = res;
      cuts_in_row = 0;
      continue;
    }
    q = q_saved;
    if (++cuts_in_row > knobs.max_cuts) fail(out.increments + 1, target, bad, res, it);
    dlambda *= 0.5;
    out.cuts++;
  }
  // Stresses and reactions at the end: the last step's update again, from the states before it
  // (after the swap, `trial` holds them).
  std::vector<double> scratch(states.committed.size());
  assembler.set_step(states.trial.data(), scratch.data(), last_dt);
  const int bad = assembler.run(q, 1.0, nullptr, r, nullptr, nullptr, &out.points);
  if (bad >= 0) fail(out.increments, 1.0, bad, out.final_residual, 0);
  out.state = states.committed;
  out.state_offset = states.offset;
  out.u_mm.resize(nn);
  out.reaction_N_mm.assign(nn, Eigen::Vector2d::Zero());
  for (int a = 0; a < nn; ++a) {
    out.u_mm[a] = assembler.u_of(q, a);
    Eigen::Vector2d rl = r.segment<2>(2 * a);
    for (int k = 0; k < 2; ++k)
      if (d.eq[2 * a + k] >= 0) rl(k) = 0.0;
    out.reaction_N_mm[a] = d.R[a] * rl;
  }
  return out;
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

Eigen::Matrix2d stress_at(const Mesh& m, const StaticSolution& s, const Eigen::Vector2d& P,
                          Integration integration, double* sigma33) {
  const int npe = m.nodes_per_element, n = gauss_order(m, integration);
  const std::vector<double> g = detail::gauss_abscissae(n);
  double N[8], dxi[8], deta[8];
  for (int e = 0; e < m.element_count(); ++e) {
    Eigen::Vector2d lo = m.X[m.elements[e][0]], hi = lo;
    for (int a = 0; a < npe; ++a) lo = lo.cwiseMin(m.X[m.elements[e][a]]), hi = hi.cwiseMax(m.X[m.elements[e][a]]);
    const double pad = 1e-9 * (1.0 + (hi - lo).norm());
    if ((P.array() < lo.array() - pad).any() || (P.array() > hi.array() + pad).any()) continue;
    Eigen::Vector2d xi = Eigen::Vector2d::Zero();  // inverse isoparametric map by Newton
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
    if (!xi.allFinite() || xi.cwiseAbs().maxCoeff() > 1.0 + 1e-7) continue;
    auto lagrange = [&](int i, double t) {
      double v = 1.0;
      for (int j = 0; j < n; ++j)
        if (j != i) v *= (t - g[j]) / (g[i] - g[j]);
      return v;
    };
    Eigen::Matrix2d sigma = Eigen::Matrix2d::Zero();
    double s33 = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double w = lagrange(i, xi.x()) * lagrange(j, xi.y());
        sigma += w * s.points[e][j * n + i].cauchy_MPa;
        s33 += w * s.points[e][j * n + i].sigma33_MPa;
      }
    if (sigma33) *sigma33 = s33;
    return sigma;
  }
  std::ostringstream msg;
  msg << "point (" << P.x() << ", " << P.y() << ") mm is outside the segment mesh";
  throw core::InputError(msg.str());
}

}  // namespace fitlib::segment
