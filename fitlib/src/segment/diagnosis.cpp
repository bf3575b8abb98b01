// Diagnosis of a failed Newton increment (diagnosis.hpp; docs/segment.md §Solver, "Failure diagnosis").
#include "diagnosis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseLU>

namespace fitlib::segment::detail {
namespace {

constexpr int kDenseLimit = 4000;  // equations: beyond it the dense eigen-solve is skipped (O(n³))

class Diagnosis {
 public:
  Diagnosis(const DiagnosisProblem& p, const Eigen::VectorXd& q) : p_(p), q_(q), m_(*p.mesh), eq_(*p.eq) {}

  std::string run(const std::string& label) {
    out_ << "\n[" << label << "] ";
    const Eigen::VectorXd r = p_.residual(q_);
    if (r.size() == 0) return out_.str() + "an element is inverted";
    const Eigen::SparseMatrix<double> K = p_.tangent(q_);
    out_ << "free residual " << free_part(r).norm() << " N/mm";
    spectrum(K);
    columns(K);
    elements();
    scan(K, r);
    sites(r);
    return out_.str();
  }

 private:
  Eigen::VectorXd free_part(const Eigen::VectorXd& r) const {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(K_size());
    for (int i = 0; i < r.size(); ++i)
      if (eq_[i] >= 0) f(eq_[i]) = r(i);
    return f;
  }
  int K_size() const { return static_cast<int>(*std::max_element(eq_.begin(), eq_.end())) + 1; }
  int node_of(int equation) const {
    return static_cast<int>(std::find(eq_.begin(), eq_.end(), equation) - eq_.begin()) / 2;
  }
  void at_node(int n) { out_ << "node " << n << " (" << m_.X[n].x() << ", " << m_.X[n].y() << " mm)"; }

  // The symmetric part's lowest eigenvalues: one near zero, far below the next, is a limit or
  // bifurcation point (its mode says where); negative ones, an unstable state.
  void spectrum(const Eigen::SparseMatrix<double>& Ks) {
    if (Ks.rows() > kDenseLimit) return;
    const Eigen::MatrixXd K(Ks);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (K + K.transpose()));
    const Eigen::VectorXd& l = eig.eigenvalues();
    int top = 0;
    eig.eigenvectors().col(0).cwiseAbs().maxCoeff(&top);
    out_ << "; lowest eigenvalues of K's symmetric part " << l(0) << ", " << l(1) << ", " << l(2) << " N/mm² (largest "
         << l(l.size() - 1) << "), " << (l.array() < 0.0).count() << " negative, lowest mode largest at ";
    const int n = node_of(top);
    at_node(n);
    // Its direction there (the node's components: global, or a constrained node's local basis).
    Eigen::Vector2d d = Eigen::Vector2d::Zero();
    for (int k = 0; k < 2; ++k)
      if (eq_[2 * n + k] >= 0) d(k) = eig.eigenvectors()(eq_[2 * n + k], 0);
    d.normalize();
    out_ << " along (" << d.x() << ", " << d.y() << ")";
  }

  // Each column of K against central differences of the free residual (h = 10⁻⁶ mm).
  void columns(const Eigen::SparseMatrix<double>& K) {
    const double h = 1e-6;
    double worst = 0.0;
    int worst_eq = -1;
    for (int i = 0; i < q_.size(); ++i) {
      if (eq_[i] < 0) continue;
      Eigen::VectorXd qp = q_, qm = q_;
      qp(i) += h, qm(i) -= h;
      const Eigen::VectorXd fd = (free_part(p_.residual(qp)) - free_part(p_.residual(qm))) / (2 * h);
      const Eigen::VectorXd k = K.col(eq_[i]);
      const double e = (fd - k).norm() / k.norm();
      if (e > worst) worst = e, worst_eq = eq_[i];
    }
    out_ << "; tangent against central differences: worst column " << worst << " at ";
    at_node(node_of(worst_eq));
  }

  // Each element's tangent against central differences of its force (h = 10⁻⁶ mm); the worst
  // element's points in detail.
  void elements() {
    double worst = 0.0;
    int worst_e = -1;
    for (int e = 0; e < m_.element_count(); ++e)
      if (const double err = element_error(e); err > worst) worst = err, worst_e = e;
    out_ << "; worst element " << worst_e << " (" << worst << ")";
    if (worst_e >= 0) points(worst_e);
  }

  double element_error(int e) const {
    ElementVector f, fp, fm;
    ElementMatrix Ke, Kfd;
    if (!p_.element(q_, e, f, &Ke, nullptr)) return std::numeric_limits<double>::infinity();
    Kfd.setZero(Ke.rows(), Ke.cols());
    const double h = 1e-6;
    for (int a = 0; a < m_.nodes_per_element; ++a)
      for (int k = 0; k < 2; ++k) {
        const int n = m_.elements[e][a];
        const Eigen::Vector2d dq = (*p_.basis)[n].transpose() * Eigen::Vector2d::Unit(k) * h;  // global e_k
        Eigen::VectorXd qp = q_, qm = q_;
        qp.segment<2>(2 * n) += dq, qm.segment<2>(2 * n) -= dq;
        p_.element(qp, e, fp, nullptr, nullptr), p_.element(qm, e, fm, nullptr, nullptr);
        Kfd.col(2 * a + k) = (fp - fm) / (2 * h);
      }
    return (Kfd - Ke).norm() / Ke.norm();
  }

  // dP/dF against central differences (h = 10⁻⁶) and the kink ‖P(F+h) − 2P(F) + P(F−h)‖/(h‖A‖)
  // over the four columns, O(h) where P is smooth, the jump of the one-sided derivatives at F
  // (relative to ‖A‖) where it kinks.
  void points(int e) {
    ElementVector f;
    std::vector<ElementState> states;
    p_.element(q_, e, f, nullptr, &states);
    const double h = 1e-6;
    for (int g = 0; g < static_cast<int>(states.size()); ++g) {
      const Eigen::Matrix2d F = states[g].F;
      const PointResponse r0 = p_.point(e, g, F, true);
      Eigen::Matrix4d fd, jump;
      for (int c = 0; c < 4; ++c) {
        Eigen::Matrix2d dF = Eigen::Matrix2d::Zero();
        dF(c / 2, c % 2) = h;
        const Eigen::Matrix2d Pp = p_.point(e, g, F + dF, false).P, Pm = p_.point(e, g, F - dF, false).P;
        const Eigen::Matrix2d central = (Pp - Pm) / (2 * h), second = (Pp - 2 * r0.P + Pm) / h;
        fd.col(c) << central(0, 0), central(0, 1), central(1, 0), central(1, 1);
        jump.col(c) << second(0, 0), second(0, 1), second(1, 0), second(1, 1);
      }
      const double err = (fd - r0.A).norm() / r0.A.norm(), kink = jump.norm() / r0.A.norm();
      const Eigen::Vector2d stretch =
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(Eigen::Matrix2d(F.transpose() * F)).eigenvalues().cwiseSqrt();
      out_ << "; point " << g << " at (" << states[g].X_mm.x() << ", " << states[g].X_mm.y() << " mm): stretches "
           << stretch(0) << ", " << stretch(1) << ", dP/dF error " << err << ", kink " << kink;
    }
  }

  // ‖r(q + αd)‖/‖r(q)‖ along Newton's direction d = −K⁻¹r: (1 − α) + O(α²) for a smooth residual and
  // a consistent tangent; a large α² term with a small ‖r‖ marks a nearly singular tangent.
  void scan(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& r) {
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(K);
    const Eigen::VectorXd d = lu.solve(-free_part(r));
    const double r0 = free_part(r).norm();
    if (!(r0 > 0.0)) return;
    out_ << "; along Newton's direction (|d| " << d.norm() << " mm) alpha: |r|/|r0|";
    for (double alpha : {-1e-2, -1e-4, 1e-6, 1e-4, 1e-3, 1e-2, 0.1, 0.5, 1.0}) {
      Eigen::VectorXd qa = q_;
      for (int i = 0; i < q_.size(); ++i)
        if (eq_[i] >= 0) qa(i) += alpha * d(eq_[i]);
      const Eigen::VectorXd ra = p_.residual(qa);
      out_ << " " << alpha << ": " << (ra.size() ? free_part(ra).norm() / r0 : std::numeric_limits<double>::infinity());
    }
  }

  // The three largest free residual entries.
  void sites(const Eigen::VectorXd& r) {
    std::vector<int> idx;
    for (int i = 0; i < r.size(); ++i)
      if (eq_[i] >= 0) idx.push_back(i);
    const std::size_t n = std::min<std::size_t>(3, idx.size());
    std::partial_sort(idx.begin(), idx.begin() + n, idx.end(), [&](int a, int b) { return std::abs(r(a)) > std::abs(r(b)); });
    out_ << "; largest residual entries";
    for (std::size_t k = 0; k < n; ++k) {
      out_ << (k ? ", " : " ") << r(idx[k]) << " N/mm at ";
      at_node(idx[k] / 2);
    }
  }

  const DiagnosisProblem& p_;
  const Eigen::VectorXd& q_;
  const Mesh& m_;
  const std::vector<int>& eq_;
  std::ostringstream out_;
};

}  // namespace

std::string diagnose(const DiagnosisProblem& problem, const Eigen::VectorXd& q, const std::string& label) {
  return Diagnosis(problem, q).run(label);
}

}  // namespace fitlib::segment::detail
