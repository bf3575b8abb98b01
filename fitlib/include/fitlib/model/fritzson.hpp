#pragma once
// Fritzson's elastomer-composite model (thesis Report II; docs/fritzson.md §1):
// volumetric/deviatoric split, isotropic deviatoric part of mean,
// rate-independent dynamic and five-element Maxwell (viscous) contributions, amplitude damage
// h1/h2 with evolution constant C_d, linear temperature factors g1/g2, and the transversely
// isotropic parts A1 (uniaxial along the fibre axis 3) and A2 (shear 13/23).
//
// Two kinds: "fritzson" (38 parameters) and "fritzson-iso" (the first 14). Options:
// {"reference_temperature_C": 23.0}. Notes with equations and line references: docs/fritzson.md.
#include <ceres/jet.h>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fitlib/core/parameter.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::model::fritzson {

// Parameter order. The isotropic model uses [0, kIsotropicCount); each part (I, A1, A2) lists
// its 12 constants in the same order starting at its offset, so PartIndex works for all three.
enum Index : int {
  kK = 0,
  kPartI = 1,  // G_Im, G_Id, G_Iv, tau_I, k_I, beta1_I, alpha1_I, mu_I, beta2_I, alpha2_I, c1_I, c2_I
  kCd = 13,
  kIsotropicCount = 14,
  kPartA1 = 14,  // C33_Am, C33_Ad, C33_Av, tau_A1, k_A1, beta1_A1, ... c2_A1
  kPartA2 = 26,  // C44_Am, C44_Ad, C44_Av, tau_A2, k_A2, beta1_A2, ... c2_A2
  kAnisotropicCount = 38,
};
// Offsets inside a part.
enum PartIndex : int {
  kMean = 0, kDynamic, kViscous, kTau, kK_ratio, kBeta1, kAlpha1, kMu, kBeta2, kAlpha2, kC1, kC2,
  kPartSize
};

// Parameter specs (names, units, bounds, log transforms, groups "volumetric", "mean", "dynamic",
// "viscous", "damage", "temperature", "A1", "A2").
std::vector<core::ParameterSpec> parameter_specs(bool anisotropic);

// Builds "fritzson" or "fritzson-iso" (options: reference_temperature_C, default 23).
ModelPtr make_fritzson_model(const std::string& kind, const nlohmann::json& options);
bool is_fritzson_kind(const std::string& kind);

// ---- scalar helpers that work for double and ceres::Jet ------------------------------------
inline double scalar_part(double x) { return x; }
template <typename U, int N>
double scalar_part(const ceres::Jet<U, N>& x) { return x.a; }

// (1 − e^{−u})/u, smooth through u = 0.
template <typename T>
T one_minus_exp_over(const T& u) {
  using std::expm1;
  if (scalar_part(u) < 1e-8) return T(1.0) - 0.5 * u;
  return -expm1(-u) / u;
}

// sqrt that is 0 with zero derivative at 0 (a norm of a zero tensor).
template <typename T>
T safe_sqrt(const T& x) {
  using std::sqrt;
  if (scalar_part(x) <= 0.0) return T(0.0);
  return sqrt(x);
}

// Smallest damage driver taken into log10; below it h1 = 1 and h2 = β2 (their limits).
constexpr double kDriverFloor = 1e-30;

// Pólya's complement ½[1 − (1 − e^{−(2/π)y²})^½ sgn y] (4.33–4.35). Near y = 0 it is evaluated as
// ½[1 − y·√((2/π)·f((2/π)y²))] with f(u) = (1 − e^{−u})/u: analytic in y, so sgn(0) = 0 and the
// derivative at y = 0 are exact (no √0). In the upper tail it is ½e^{−u}/(1 + √(1 − e^{−u})),
// which stays positive and accurate (no cancellation to 0 or below).
template <typename T>
T polya_complement(const T& y) {
  using std::exp;
  using std::expm1;
  using std::sqrt;
  constexpr double kTwoOverPi = 0.63661977236758134;
  const T u = kTwoOverPi * y * y;
  const double ys = scalar_part(y);
  if (ys > -0.5 && ys < 0.5) return 0.5 * (T(1.0) - y * sqrt(kTwoOverPi * one_minus_exp_over(u)));
  const T upper_tail = 0.5 * exp(-u) / (T(1.0) + sqrt(-expm1(-u)));
  return ys > 0.0 ? upper_tail : T(1.0) - upper_tail;
}

// Elastic damage h1 (4.35): 1 at small driver, β1 at large; x = log10(driver).
template <typename T, typename D>
T damage_h1(const D& driver, const T& beta1, const T& alpha1, const T& mu) {
  using std::log10;
  if (scalar_part(driver) < kDriverFloor) return T(1.0);
  const T y = (log10(driver) - mu) / alpha1;
  return beta1 + (T(1.0) - beta1) * polya_complement(y);
}

// Viscous damage h2 (4.36 with decisions): Gaussian in log10(driver) normalised to peak 1 at μ,
// → β2 far from μ.
template <typename T, typename D>
T damage_h2(const D& driver, const T& beta2, const T& alpha2, const T& mu) {
  using std::exp;
  using std::log10;
  if (scalar_part(driver) < kDriverFloor) return beta2;
  const T y = (log10(driver) - mu) / alpha2;
  return beta2 + (T(1.0) - beta2) * exp(-0.5 * y * y);
}

// Reversible linear temperature factor g = 1 − c (T − T_ref), floored at kTemperatureFloor.
constexpr double kTemperatureFloor = 1e-3;
template <typename T>
T temperature_factor(const T& c, double temperature_C, double reference_C) {
  if (std::isnan(temperature_C)) return T(1.0);
  const T g = T(1.0) - c * (temperature_C - reference_C);
  return scalar_part(g) < kTemperatureFloor ? T(kTemperatureFloor) : g;
}

// The five relaxation times of a Maxwell group: τ, τk, τ/k, τk², τ/k² (4.44–4.48).
template <typename T>
void maxwell_times(const T& tau, const T& k, T out[5]) {
  out[0] = tau;
  out[1] = tau * k;
  out[2] = tau / k;
  out[3] = tau * k * k;
  out[4] = tau / (k * k);
}

// Σ iωτ_n/(1 + iωτ_n) over the group: (S′, S″).
template <typename T>
std::complex<T> maxwell_group_response(double omega_rad_s, const T& tau, const T& k) {
  T times[5];
  maxwell_times(tau, k, times);
  T re(0.0), im(0.0);
  for (const T& t : times) {
    const T x = omega_rad_s * t;
    const T d = T(1.0) + x * x;
    re += x * x / d;
    im += x / d;
  }
  return {re, im};
}

// Damage and temperature factors of one part at a given steady driver amplitude.
template <typename T>
struct PartFactors {
  T h1, h2, g1, g2;
};

template <typename T, typename D>
PartFactors<T> part_factors(const T* part, const D& driver, double temperature_C,
                            double reference_C) {
  return {damage_h1(driver, part[kBeta1], part[kAlpha1], part[kMu]),
          damage_h2(driver, part[kBeta2], part[kAlpha2], part[kMu]),
          temperature_factor(part[kC1], temperature_C, reference_C),
          temperature_factor(part[kC2], temperature_C, reference_C)};
}

// Steady sinusoidal response of one deviatoric part (damage saturated): the complex modulus M*
// (s = 2M*e for I and A1 on the e3 measure, s = M*γ for A2) and the static modulus M_m.
template <typename T>
struct PartModuli {
  std::complex<T> dynamic;
  T mean;
};

template <typename T>
PartModuli<T> part_moduli(const T* part, const PartFactors<T>& f, double omega_rad_s) {
  const T elastic = f.h1 * f.g1;
  const std::complex<T> group = maxwell_group_response(omega_rad_s, part[kTau], part[kK_ratio]);
  const T viscous = f.h2 * f.g2 * part[kViscous];
  return {std::complex<T>(elastic * (part[kMean] + part[kDynamic]) + viscous * group.real(),
                          viscous * group.imag()),
          elastic * part[kMean]};
}

}  // namespace fitlib::model::fritzson
