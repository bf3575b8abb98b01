#pragma once
// Bernstein polynomials B_{i,d}(t) = C(d,i) t^i (1-t)^(d-i) (Report V Eq 5.2 for d = 2), the
// blending functions of the Bezier surfaces. Evaluated by the de Casteljau-style recurrence, which
// is stable on [0, 1] and gives exact zeros of B_{i,d}(1) for i < d (so face constraints at t = 1
// touch only the last control points, as in Eqs 5.30-5.32).
#include <cstddef>

namespace fitlib::surface {

// b[0..d] = B_{i,d}(t).
inline void bernstein(int d, double t, double* b) {
  const double s = 1.0 - t;
  b[0] = 1.0;
  for (int k = 1; k <= d; ++k) {
    b[k] = t * b[k - 1];
    for (int i = k - 1; i > 0; --i) b[i] = s * b[i] + t * b[i - 1];
    b[0] *= s;
  }
}

// b[0..d] = B_{i,d}(t) and db[0..d] = dB_{i,d}/dt = d (B_{i-1,d-1} - B_{i,d-1}).
inline void bernstein_with_derivative(int d, double t, double* b, double* db) {
  if (d == 0) {
    b[0] = 1.0;
    db[0] = 0.0;
    return;
  }
  bernstein(d - 1, t, b);  // degree d-1 first, then derivative, then raise to degree d
  db[0] = -d * b[0];
  for (int i = 1; i < d; ++i) db[i] = d * (b[i - 1] - b[i]);
  db[d] = d * b[d - 1];
  const double s = 1.0 - t;
  b[d] = t * b[d - 1];
  for (int i = d - 1; i > 0; --i) b[i] = s * b[i] + t * b[i - 1];
  b[0] *= s;
}

// Coefficient of c_{i+k} in the m-th forward difference Δ^m c_i = Σ_k (-1)^(m-k) C(m,k) c_{i+k}.
// ∂^m/∂t^m of a degree-d Bezier curve is d!/(d-m)! Σ_i Δ^m c_i B_{i,d-m}(t), so it vanishes for
// all t exactly when Δ^m c_i = 0 for i = 0..d-m (for d = m = 2: c_2 - 2 c_1 + c_0 = 0).
inline double forward_difference_coefficient(int m, int k) {
  double binomial = 1.0;
  for (int j = 1; j <= k; ++j) binomial = binomial * (m - k + j) / j;
  return ((m - k) % 2 == 0) ? binomial : -binomial;
}

}  // namespace fitlib::surface
