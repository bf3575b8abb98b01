// The moulded reference and the cord curve of a load-cycle run (cycle_parts.hpp; docs/segment.md
// "Loading by the load cycle").
#include <algorithm>
#include <cmath>

#include "cycle_parts.hpp"

namespace fitlib::segment::detail {

Mesh wrapped(const Mesh& straight, double K_m) {
  Mesh m = straight;
  const NeutralCurve mould = NeutralCurve::uniform(K_m, 0.0, 1.5 * straight.half_length_mm);
  for (Eigen::Vector2d& X : m.X) {
    const CurvePoint q = mould.at(X.x());
    X = Eigen::Vector2d(q.x_mm, q.y_mm) + X.y() * Eigen::Vector2d(std::sin(q.phi_rad), std::cos(q.phi_rad));
  }
  return m;
}

// state; step 2 reads the history at s0 + ξ, s0 = (τ − 1) L. Each interval's curvature is the
// history's mean over it (not a sample at its middle), so the curve moves continuously in τ when
// a curvature jump (a pulley's entrance) passes through the segment (docs/decisions.md).
NeutralCurve cord_curve(double tau, const belt::LoadHistory& h, const CurvatureIntegral& integral, double K_m,
                        double reach_mm, int n) {
  const double w = std::min(1.0, tau), s0 = std::max(0.0, tau - 1.0) * h.length_mm();
  const double ds = reach_mm / n;
  std::array<std::vector<double>, 2> K, eps;
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    for (int i = 0; i <= n; ++i) {
      eps[side].push_back(w * h.at_position(s0 + sign * i * ds).strain);
      if (i == n) break;
      const double mean = (integral(s0 + sign * (i + 1) * ds) - integral(s0 + sign * i * ds)) / (sign * ds);
      K[side].push_back((1.0 - w) * K_m + w * mean);
    }
  }
  return NeutralCurve(ds, K[0], eps[0], K[1], eps[1]);
}

}  // namespace fitlib::segment::detail
