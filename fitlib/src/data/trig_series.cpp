// Trigonometric polynomials of the waveform analysis; see trig_series.hpp.
#include "trig_series.hpp"

#include <algorithm>

#include "fitlib/core/units.hpp"

namespace fitlib::data::trig {
namespace {
constexpr double kTwoPi = 2.0 * core::kPi;
}  // namespace

Eigen::MatrixXd trig_basis(const std::vector<double>& theta, int degree) {
  Eigen::MatrixXd basis(static_cast<Eigen::Index>(theta.size()), 2 * degree + 1);
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    basis(row, 0) = 1.0;
    for (int k = 1; k <= degree; ++k) {
      basis(row, 2 * k - 1) = std::cos(k * theta[i]);
      basis(row, 2 * k) = std::sin(k * theta[i]);
    }
  }
  return basis;
}

TrigSeries series_from(const Eigen::VectorXd& coefficients, int degree) {
  TrigSeries s;
  s.c = coefficients[0];
  s.a.resize(degree);
  s.b.resize(degree);
  for (int k = 1; k <= degree; ++k) {
    s.a[k - 1] = coefficients[2 * k - 1];
    s.b[k - 1] = coefficients[2 * k];
  }
  return s;
}

// Largest and smallest value of a trigonometric polynomial over one period: a dense scan, then
// Newton steps on p′ = 0 from the best grid points.
std::pair<double, double> extremes(const TrigSeries& p) {
  const int grid = std::max(256, 32 * p.degree());
  int i_max = 0, i_min = 0;
  double v_max = -HUGE_VAL, v_min = HUGE_VAL;
  for (int i = 0; i < grid; ++i) {
    const double v = p.value(kTwoPi * i / grid);
    if (v > v_max) v_max = v, i_max = i;
    if (v < v_min) v_min = v, i_min = i;
  }
  const auto polish = [&](int start, double best, bool is_max) {
    double theta = kTwoPi * start / grid;
    for (int iteration = 0; iteration < 20; ++iteration) {
      const double curvature = p.curvature(theta);
      if (curvature == 0.0 || (is_max ? curvature > 0.0 : curvature < 0.0)) break;
      const double step = p.slope(theta) / curvature;
      theta -= std::clamp(step, -kTwoPi / grid, kTwoPi / grid);
      const double v = p.value(theta);
      best = is_max ? std::max(best, v) : std::min(best, v);
      if (std::abs(step) < 1e-15) break;
    }
    return best;
  };
  return {polish(i_max, v_max, true), polish(i_min, v_min, false)};
}

double refine_angular_frequency(const std::vector<double>& time_s, const std::vector<double>& y,
                                double omega, int degree, std::vector<std::string>& warnings) {
  const double t0 = 0.5 * (time_s.front() + time_s.back());
  const Eigen::Index n = static_cast<Eigen::Index>(y.size());
  const Eigen::Map<const Eigen::VectorXd> observed(y.data(), n);
  const auto phases = [&](double w) {
    std::vector<double> theta(y.size());
    for (std::size_t i = 0; i < y.size(); ++i) theta[i] = w * (time_s[i] - t0);
    return theta;
  };
  const double omega_start = omega;
  Eigen::VectorXd coefficients =
      trig_basis(phases(omega), degree).colPivHouseholderQr().solve(observed);
  for (int iteration = 0; iteration < 50; ++iteration) {
    const std::vector<double> theta = phases(omega);
    Eigen::MatrixXd jacobian(n, 2 * degree + 2);
    jacobian.leftCols(2 * degree + 1) = trig_basis(theta, degree);
    const TrigSeries p = series_from(coefficients, degree);
    for (Eigen::Index i = 0; i < n; ++i)
      jacobian(i, 2 * degree + 1) = (time_s[i] - t0) * p.slope(theta[i]);
    const Eigen::VectorXd residual = observed - jacobian.leftCols(2 * degree + 1) * coefficients;
    const Eigen::VectorXd step = jacobian.colPivHouseholderQr().solve(residual);
    coefficients += step.head(2 * degree + 1);
    omega += step[2 * degree + 1];
    if (std::abs(step[2 * degree + 1]) <= 1e-15 * omega) break;
  }
  if (!(std::abs(omega / omega_start - 1.0) < 0.05)) {
    warnings.push_back("frequency refinement did not converge; zero-crossing estimate used");
    return omega_start;
  }
  return omega;
}

}  // namespace fitlib::data::trig
