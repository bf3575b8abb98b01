#pragma once
// Private: the strain energies of model/hyperelastic.hpp, templated on the scalar (double or
// ceres::Jet) so fits get exact derivatives. `tau` is the analytic route (λ_i ∂W/∂λ_i at J = 1),
// `energy` the independent one the tests differentiate numerically.
#include <ceres/jet.h>

#include <cmath>
#include <vector>

#include "fitlib/model/hyperelastic.hpp"

namespace fitlib::model::hyper {

using std::log;
using std::pow;
using std::sqrt;

// Arruda–Boyce series coefficients c_1..c_5 (Abaqus Theory Manual, Arruda–Boyce form).
constexpr double kArrudaBoyce[5] = {0.5, 1.0 / 20.0, 11.0 / 1050.0, 19.0 / 7000.0, 519.0 / 673750.0};

template <typename T>
T ipow(const T& x, int n) {
  T r(1.0);
  for (int k = 0; k < n; ++k) r *= x;
  return r;
}

struct Structure {
  HyperelasticFamily family = HyperelasticFamily::neo_hooke;
  std::vector<std::pair<int, int>> exponents;  // polynomial families: (i, j) of each C_ij, in parameter order
  int ogden_terms = 0;
  bool compressible = false;
  int size() const {
    const int base = family == HyperelasticFamily::ogden ? 2 * ogden_terms
                     : (family == HyperelasticFamily::arruda_boyce || family == HyperelasticFamily::gent)
                         ? 2
                         : static_cast<int>(exponents.size());
    return base + (compressible ? 1 : 0);
  }
  int d1_index() const { return compressible ? size() - 1 : -1; }
};

// ∂W/∂Ī1 and ∂W/∂Ī2 of the invariant laws.
template <typename T>
void invariant_derivatives(const Structure& s, const T* p, const T& I1, const T& I2, T& W1, T& W2) {
  W1 = T(0.0), W2 = T(0.0);
  switch (s.family) {
    case HyperelasticFamily::arruda_boyce: {
      const T lm2 = p[1] * p[1];
      T scale(1.0);
      for (int k = 1; k <= 5; ++k) {
        W1 += p[0] * kArrudaBoyce[k - 1] * double(k) * ipow(I1, k - 1) / scale;
        scale *= lm2;
      }
      return;
    }
    case HyperelasticFamily::gent:
      W1 = 0.5 * p[0] / (T(1.0) - (I1 - 3.0) / p[1]);
      return;
    default:
      for (std::size_t k = 0; k < s.exponents.size(); ++k) {
        const auto [i, j] = s.exponents[k];
        if (i > 0) W1 += double(i) * p[k] * ipow(I1 - 3.0, i - 1) * ipow(I2 - 3.0, j);
        if (j > 0) W2 += double(j) * p[k] * ipow(I1 - 3.0, i) * ipow(I2 - 3.0, j - 1);
      }
  }
}

// τ_i = λ_i ∂W/∂λ_i of the isochoric energy at stretches with λ1 λ2 λ3 = 1 (up to a common
// hydrostatic part, which incompressibility leaves undetermined).
template <typename T>
void tau(const Structure& s, const T* p, const T lam[3], T out[3]) {
  if (s.family == HyperelasticFamily::ogden) {
    for (int i = 0; i < 3; ++i) out[i] = T(0.0);
    for (int k = 0; k < s.ogden_terms; ++k) {
      const T& mu = p[2 * k];
      const T& alpha = p[2 * k + 1];
      for (int i = 0; i < 3; ++i) out[i] += 2.0 * mu / alpha * pow(lam[i], alpha);
    }
    return;
  }
  const T l2[3] = {lam[0] * lam[0], lam[1] * lam[1], lam[2] * lam[2]};
  const T I1 = l2[0] + l2[1] + l2[2];
  const T I2 = l2[0] * l2[1] + l2[1] * l2[2] + l2[2] * l2[0];
  T W1, W2;
  invariant_derivatives(s, p, I1, I2, W1, W2);
  // ∂I1/∂λ_i = 2 λ_i, ∂I2/∂λ_i = 2 λ_i (I1 − λ_i²).
  for (int i = 0; i < 3; ++i) out[i] = 2.0 * l2[i] * (W1 + (I1 - l2[i]) * W2);
}

// The isochoric energy at stretches with λ1 λ2 λ3 = 1.
template <typename T>
T isochoric_energy(const Structure& s, const T* p, const T lam[3]) {
  if (s.family == HyperelasticFamily::ogden) {
    T W(0.0);
    for (int k = 0; k < s.ogden_terms; ++k) {
      const T& mu = p[2 * k];
      const T& alpha = p[2 * k + 1];
      W += 2.0 * mu / (alpha * alpha) * (pow(lam[0], alpha) + pow(lam[1], alpha) + pow(lam[2], alpha) - 3.0);
    }
    return W;
  }
  const T I1 = lam[0] * lam[0] + lam[1] * lam[1] + lam[2] * lam[2];
  const T I2 = lam[0] * lam[0] * lam[1] * lam[1] + lam[1] * lam[1] * lam[2] * lam[2] + lam[2] * lam[2] * lam[0] * lam[0];
  switch (s.family) {
    case HyperelasticFamily::arruda_boyce: {
      T W(0.0), scale(1.0);
      for (int k = 1; k <= 5; ++k) {
        W += p[0] * kArrudaBoyce[k - 1] * (ipow(I1, k) - std::pow(3.0, k)) / scale;
        scale *= p[1] * p[1];
      }
      return W;
    }
    case HyperelasticFamily::gent:
      return -0.5 * p[0] * p[1] * log(T(1.0) - (I1 - 3.0) / p[1]);
    default: {
      T W(0.0);
      for (std::size_t k = 0; k < s.exponents.size(); ++k)
        W += p[k] * ipow(I1 - 3.0, s.exponents[k].first) * ipow(I2 - 3.0, s.exponents[k].second);
      return W;
    }
  }
}

// U(J) and U'(J).
template <typename T>
T volumetric_energy(const Structure& s, const T* p, const T& J) {
  const T& D1 = p[s.d1_index()];
  if (s.family == HyperelasticFamily::arruda_boyce) return ((J * J - 1.0) / 2.0 - log(J)) / D1;
  return (J - 1.0) * (J - 1.0) / D1;
}
template <typename T>
T volumetric_slope(const Structure& s, const T* p, const T& J) {
  const T& D1 = p[s.d1_index()];
  if (s.family == HyperelasticFamily::arruda_boyce) return (J - 1.0 / J) / D1;
  return 2.0 * (J - 1.0) / D1;
}

// Nominal stress of a mode (docs/hyperelastic.md §"Test modes"): σ_i = τ_i − τ_3 (σ3 = 0) and
// P = σ1/λ; simple shear σ12 = (τ1 − τ2) γ/(λ1² − λ2²); volumetric p = −U'(J).
template <typename T>
T nominal_stress(const Structure& s, const T* p, DeformationMode mode, double x) {
  T lam[3], t[3];
  switch (mode) {
    case DeformationMode::uniaxial: lam[0] = T(x), lam[1] = lam[2] = T(1.0 / std::sqrt(x)); break;
    case DeformationMode::equibiaxial: lam[0] = lam[1] = T(x), lam[2] = T(1.0 / (x * x)); break;
    case DeformationMode::planar: lam[0] = T(x), lam[1] = T(1.0), lam[2] = T(1.0 / x); break;
    case DeformationMode::simple_shear: {
      if (x == 0.0) return T(0.0);
      const double l1 = 0.5 * x + std::sqrt(1.0 + 0.25 * x * x);
      lam[0] = T(l1), lam[1] = T(1.0 / l1), lam[2] = T(1.0);
      tau(s, p, lam, t);
      return (t[0] - t[1]) * (x / (l1 * l1 - 1.0 / (l1 * l1)));
    }
    case DeformationMode::volumetric: return -volumetric_slope(s, p, T(x));
  }
  tau(s, p, lam, t);
  return (t[0] - t[2]) / x;
}

}  // namespace fitlib::model::hyper
