#pragma once
// 3-point Gauss–Legendre rule on [a, b] (exact for polynomials of degree ≤ 5): the beam section's
// integrals over a layer's depth (fatigue/beam_section.cpp, scene/heat_effects.cpp) and the segment's
// end-face tractions (segment/cycle_loads.cpp).
#include <array>

namespace fitlib::core {

struct QuadraturePoint {
  double x;            // the node in [a, b]
  double weight;       // its weight for ∫ f over [a, b]
  double mean_weight;  // its weight for the mean of f over [a, b]
};

inline std::array<QuadraturePoint, 3> gauss_legendre_3(double a, double b) {
  static constexpr double node[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static constexpr double w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  std::array<QuadraturePoint, 3> out{};
  for (int k = 0; k < 3; ++k)
    out[k] = {0.5 * (a + b) + 0.5 * (b - a) * node[k], 0.5 * (b - a) * w[k], 0.5 * w[k]};
  return out;
}

}  // namespace fitlib::core
