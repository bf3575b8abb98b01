#include "fitlib/fatigue/crack_plane.hpp"

#include <cmath>
#include <vector>

#include "fitlib/core/units.hpp"

namespace fitlib::fatigue {

CrackPlaneStress crack_plane_stress(const PlaneStress& s, double theta) {
  const double c = std::cos(theta), d = std::sin(theta);
  CrackPlaneStress out;
  out.normal_MPa = s.s11_MPa * d * d + s.s22_MPa * c * c - 2.0 * s.s12_MPa * d * c;
  out.shear_MPa = (s.s22_MPa - s.s11_MPa) * d * c + s.s12_MPa * (c * c - d * d);
  return out;
}

double effective_stress_MPa(const CrackPlaneStress& c) {
  return c.normal_MPa >= 0.0 ? std::hypot(c.normal_MPa, c.shear_MPa) : std::abs(c.shear_MPa);
}

double worst_radial_crack_stress_MPa(const PlaneStress& s, double sweep, double* worst_angle) {
  // Mohr's circle in θ: σ = m + r cos 2(θ − θ0), τ = −r sin 2(θ − θ0) (up to sign), so
  // σ² + τ² and |τ| are stationary where 2(θ − θ0) is a multiple of π/2, and σ = 0 where
  // cos 2(θ − θ0) = −m/r.
  const double m = 0.5 * (s.s11_MPa + s.s22_MPa);
  const double r = std::hypot(0.5 * (s.s22_MPa - s.s11_MPa), s.s12_MPa);
  const double theta0 = 0.5 * std::atan2(-s.s12_MPa, 0.5 * (s.s22_MPa - s.s11_MPa));
  std::vector<double> candidates = {-sweep, sweep};
  auto add_family = [&](double base, double period) {
    for (int k = -8; k <= 8; ++k) {
      const double th = base + k * period;
      if (th > -sweep && th < sweep) candidates.push_back(th);
    }
  };
  add_family(theta0, 0.25 * core::kPi);
  if (r > 0.0 && std::abs(m) <= r) {
    const double a = 0.5 * std::acos(-m / r);
    add_family(theta0 + a, core::kPi);
    add_family(theta0 - a, core::kPi);
  }
  double best = -1.0, best_angle = 0.0;
  for (double th : candidates) {
    const double v = effective_stress_MPa(crack_plane_stress(s, th));
    if (v > best) best = v, best_angle = th;
  }
  if (worst_angle) *worst_angle = best_angle;
  return best;
}

double separation_stress_MPa(const PlaneStress& s) {
  return effective_stress_MPa({s.s11_MPa, s.s12_MPa});
}

}  // namespace fitlib::fatigue
