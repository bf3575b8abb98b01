#pragma once
// The parameter covariance of a least-squares fit from its Jacobian at the solution, shared by the
// viscoelastic fits (covariance.cpp) and the hyperelastic ones (hyperelastic.cpp): the SVD of the
// column-scaled Jacobian, so that the rank test and the condition number do not depend on the
// parameters' units.
#include <utility>

#include <Eigen/Core>

namespace fitlib::fit::detail {

// σ_i / σ_max below this: a null-space direction.
constexpr double kRankTolerance = 1e-8;

struct ScaledSpectrum {
  Eigen::VectorXd norms;  // column norms of the Jacobian
  Eigen::VectorXd sigma;  // one value per column, zero-padded
  Eigen::MatrixXd v;      // right singular vectors (scaled parameters)
  int rank = 0;
  double condition_number = 0.0;
};

// The spectrum of the Jacobian's columns scaled by their norms (scaled_spectrum below).
ScaledSpectrum spectrum_of_scaled(Eigen::MatrixXd scaled, Eigen::VectorXd norms);

// `jac`: m × n, either storage order (read as it is stored, so a fit's numbers do not move with it).
template <class Jacobian>
ScaledSpectrum scaled_spectrum(const Jacobian& jac) {
  const Eigen::Index m = jac.rows(), nf = jac.cols();
  Eigen::VectorXd norms(nf);
  for (Eigen::Index k = 0; k < nf; ++k) norms[k] = jac.col(k).norm();
  Eigen::MatrixXd scaled(m, nf);
  for (Eigen::Index k = 0; k < nf; ++k)
    scaled.col(k) = norms[k] > 0.0 ? Eigen::VectorXd(jac.col(k) / norms[k]) : Eigen::VectorXd::Zero(m);
  return spectrum_of_scaled(std::move(scaled), std::move(norms));
}

// The pseudo-inverse on the identifiable subspace: Cov_x = s² D⁻¹ V Σ⁻² Vᵀ D⁻¹ (D: the column norms;
// a column without effect has zero variance and covariance).
Eigen::MatrixXd scaled_covariance(const ScaledSpectrum& sp, double s2);

}  // namespace fitlib::fit::detail
