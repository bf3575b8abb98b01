// The column-scaled Jacobian's spectrum and the covariance from it (scaled_spectrum.hpp).
#include "scaled_spectrum.hpp"

#include <algorithm>

#include <Eigen/QR>
#include <Eigen/SVD>

namespace fitlib::fit::detail {

ScaledSpectrum spectrum_of_scaled(Eigen::MatrixXd scaled, Eigen::VectorXd norms) {
  const int m = static_cast<int>(scaled.rows()), nf = static_cast<int>(scaled.cols());
  ScaledSpectrum out;
  out.norms = std::move(norms);
  // SVD of the small triangular factor instead of the tall matrix.
  Eigen::MatrixXd small;
  if (m > nf) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(scaled);
    small = qr.matrixQR().topRows(nf).triangularView<Eigen::Upper>();
  } else {
    small = scaled;
  }
  // Divide and conquer: the cards' numbers to rounding, and faster than one-sided Jacobi on the
  // smooth spectrum's 50-odd terms (docs/decisions.md, "the covariance's SVD is ... BDCSVD").
  Eigen::BDCSVD<Eigen::MatrixXd> svd(small, Eigen::ComputeFullV);
  const Eigen::VectorXd sigma = svd.singularValues();
  out.v = svd.matrixV();
  const double sigma_max = sigma.size() ? sigma[0] : 0.0;
  out.sigma = Eigen::VectorXd::Zero(nf);
  out.sigma.head(sigma.size()) = sigma;
  for (int k = 0; k < nf; ++k)
    if (sigma_max > 0.0 && out.sigma[k] > kRankTolerance * sigma_max) ++out.rank;
  const double sigma_min = nf ? std::max(out.sigma[nf - 1], sigma_max * 1e-16) : 0.0;
  out.condition_number = sigma_max > 0.0 ? sigma_max / sigma_min : 0.0;
  return out;
}

Eigen::MatrixXd scaled_covariance(const ScaledSpectrum& sp, double s2) {
  const int nf = static_cast<int>(sp.norms.size());
  Eigen::MatrixXd cov_scaled = Eigen::MatrixXd::Zero(nf, nf);
  for (int d = 0; d < sp.rank; ++d) cov_scaled += sp.v.col(d) * sp.v.col(d).transpose() / (sp.sigma[d] * sp.sigma[d]);
  Eigen::MatrixXd cov_x(nf, nf);
  for (int a = 0; a < nf; ++a)
    for (int b = 0; b < nf; ++b) {
      const double da = sp.norms[a] > 0.0 ? 1.0 / sp.norms[a] : 0.0;
      const double db = sp.norms[b] > 0.0 ? 1.0 / sp.norms[b] : 0.0;
      cov_x(a, b) = s2 * da * db * cov_scaled(a, b);
    }
  return cov_x;
}

}  // namespace fitlib::fit::detail
