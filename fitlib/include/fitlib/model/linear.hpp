#pragma once
// The linear viscoelastic family (README.md, "Models"; docs/model.md), one kernel each:
//   prony             M∞ + Σ M_i·iωτ_i/(1 + iωτ_i)                       (generalized Maxwell)
//   zener3            S(1 + iωτ_ε)/(1 + iωτ_T)                           (Sorge–Cammalleri Eq. 1)
//   retardation       M* = 1/J*, J* = J_g + Σ L_i/(1 + iωλ_i)            (Zupancic–Emri Eq. 3)
//   fractional-zener  M_0 + ΔM·(iωτ)^α/(1 + (iωτ)^α)                    (Cole–Cole form)
// Common options, handled by one wrapper for every kernel:
//   "mode": "shear" | "uniaxial" | "bulk"  the modulus the kernel describes (default shear);
//   "terms": N                             prony / retardation term count (default 4);
//   "temperature_law": "none" | "wlf" | "arrhenius", "reference_C": T_ref (default 23);
//   "vertical_shift": true                 entropic factor T/T_ref (absolute temperatures);
//   "linear_factor": true                  g(T) = 1 − c_T (T − T_ref), guarded g ≥ 1e-3;
//   "bulk_modulus": true                   a constant bulk modulus K: converts between shear and
//                                          uniaxial (E* = 9KG*/(3K + G*)) and answers bulk tests.
#include <nlohmann/json.hpp>
#include <string>

#include "fitlib/model/model.hpp"

namespace fitlib::model {

// The ranges of the options "terms" and "polynomial_degree" (a polynomial shift law's degree).
constexpr int kMaxSeriesTerms = 200;
constexpr int kMaxShiftPolynomialDegree = 6;

bool is_linear_kind(const std::string& kind);
ModelPtr make_linear_model(const std::string& kind, const nlohmann::json& options);

// Fractional Zener in the time domain: the Cole–Cole relaxation spectrum discretised on a
// log grid (trapezoidal rule, exponentially convergent) as a Maxwell series. The accuracy knobs
// are the modes per decade and the decades covered each side of τ.
struct FractionalQuadrature {
  int modes_per_decade = 8;
  double decades_each_side = 16.0;
};

}  // namespace fitlib::model
