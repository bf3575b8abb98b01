// The eigenpair of a tangent's symmetric part nearest zero (critical_mode.hpp).
#include "critical_mode.hpp"

#include <cmath>

#include <Eigen/SparseCholesky>

namespace fitlib::segment::detail {

CriticalMode critical_mode(const Eigen::SparseMatrix<double>& K, int max_iterations, double tolerance) {
  CriticalMode out;
  const Eigen::SparseMatrix<double> Ks = 0.5 * (K + Eigen::SparseMatrix<double>(K.transpose()));
  // LDLᵀ without pivoting serves an indefinite K_s as long as no pivot vanishes (info() says).
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Ks);
  if (ldlt.info() != Eigen::Success) return out;
  out.negative = static_cast<int>((ldlt.vectorD().array() < 0.0).count());
  // A start with a share of every eigenvector (a smooth one could miss a local mode's sign pattern).
  Eigen::VectorXd x(Ks.rows());
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = 1.0 + 0.5 * std::sin(1.7 * static_cast<double>(i));
  x.normalize();
  double rayleigh = x.dot(Ks * x);
  for (int it = 1; it <= max_iterations; ++it) {
    Eigen::VectorXd y = ldlt.solve(x);
    if (!y.allFinite() || y.norm() == 0.0) return out;
    x = y / y.norm();
    const double next = x.dot(Ks * x);
    out.iterations = it;
    const bool settled = std::abs(next - rayleigh) <= tolerance * std::abs(next);
    rayleigh = next;
    if (settled) {
      out.found = true;
      break;
    }
  }
  out.eigenvalue = rayleigh, out.mode = x;
  return out;
}

}  // namespace fitlib::segment::detail
