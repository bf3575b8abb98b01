#pragma once
// Non-negative least squares, min ‖A x − b‖ subject to x ≥ 0 (Lawson–Hanson active set).
#include <Eigen/Core>

namespace fitlib::fit {

struct NnlsResult {
  Eigen::VectorXd x;
  double residual_norm = 0.0;  // ‖A x − b‖
  int iterations = 0;
  bool converged = false;      // KKT conditions verified on A itself
  double kkt_violation = 0.0;  // max over zero entries of the scaled gradient Aᵀ(b − A x)
  bool used_qr = false;        // the normal-equation pass failed the check; QR pass used
};

// Solves with column scaling; first on the normal equations (fast: one small Cholesky per
// active-set change), then checks the KKT conditions against A and falls back to QR solves of
// the passive columns when the check fails (ill-conditioned A).
NnlsResult nnls(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, int max_iterations = 0);

}  // namespace fitlib::fit
