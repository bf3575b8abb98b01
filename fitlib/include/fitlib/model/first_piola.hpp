#pragma once
// The material-point contract in the form a total-Lagrangian FE code needs (docs/model.md
// §"First Piola–Kirchhoff form"): from F, the point's unrotated Kirchhoff stress τ_U(ln U) and its
// tangent D = dτ_U/d(ln U), the first Piola–Kirchhoff stress
//     S = U⁻¹ τ_U U⁻¹ (second Piola–Kirchhoff),  P = F S   (so τ = P Fᵀ = R τ_U Rᵀ)
// and the consistent tangent dP/dF = dF S + F dS with
//     dS = dW τ_U W + W (D : d ln U) W + W τ_U dW,  W = U⁻¹,
// d ln U and dW from dC = dFᵀF + FᵀdF by the spectral (Daleckii–Krein) derivative of the
// isotropic tensor functions ½ ln C and C^(−1/2).
#include <Eigen/Core>

#include "fitlib/model/material_point.hpp"

namespace fitlib::model {

using Matrix9 = Eigen::Matrix<double, 9, 9>;  // dP_iJ/dF_kL at (3i+J, 3k+L)

struct FirstPiolaResult {
  Eigen::Matrix3d P;             // MPa
  Vector6 stress_unrotated;      // τ_U (Voigt), MPa
  Matrix9 dP_dF;                 // set when asked; columns not asked are zero
};

// Which columns of dP/dF to form: all nine, or only the in-plane ones (F_11, F_12, F_21, F_22) a
// plane-strain code needs (F_33 = 1 and the out-of-plane shears stay zero there).
enum class TangentColumns { none, all, in_plane };

// One update of `point` at the deformation gradient F (material axes; det F > 0, else
// NumericalError), as MaterialPoint::update: reads state_n, writes state_next.
FirstPiolaResult first_piola(const MaterialPoint& point, const double* state_n, const Eigen::Matrix3d& F,
                             double dt_s, double temperature_C, double* state_next,
                             TangentColumns columns = TangentColumns::all);

// Spectral derivative of an isotropic function f of a symmetric C = Q diag(c) Qᵀ in the
// direction dC: Q (Θ ∘ QᵀdC Q) Qᵀ with Θ_ab the divided difference f[c_a, c_b] (f'(c_a) on the
// diagonal). `theta` holds Θ.
Eigen::Matrix3d spectral_derivative(const Eigen::Matrix3d& Q, const Eigen::Matrix3d& theta,
                                    const Eigen::Matrix3d& dC);

}  // namespace fitlib::model
