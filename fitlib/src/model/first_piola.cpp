// First Piola–Kirchhoff stress and dP/dF of a material point (fitlib/model/first_piola.hpp).
#include "fitlib/model/first_piola.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "fitlib/core/error.hpp"
#include "in_plane_point.hpp"

namespace fitlib::model {
namespace {

// ½ (ln a − ln b)/(a − b), stable as a → b (series of ln(1 + r)/r).
double half_log_divided(double a, double b) {
  const double r = a / b - 1.0;
  if (std::abs(r) < 1e-6) return 0.5 * (1.0 - r / 2.0 + r * r / 3.0) / b;
  return 0.5 * std::log1p(r) / (r * b);
}

// (a^(−½) − b^(−½))/(a − b) = −1/(√a √b (√a + √b)), exact also at a = b.
double inverse_sqrt_divided(double a, double b) {
  const double sa = std::sqrt(a), sb = std::sqrt(b);
  return -1.0 / (sa * sb * (sa + sb));
}

// Θ of ½ ln c and c^(−½) over the eigenvalues c (spectral_derivative).
template <int N>
void divided_differences(const Eigen::Matrix<double, N, 1>& c, Eigen::Matrix<double, N, N>& theta_log,
                         Eigen::Matrix<double, N, N>& theta_w) {
  for (int a = 0; a < N; ++a)
    for (int b = a; b < N; ++b) {  // symmetric: f[c_a, c_b] = f[c_b, c_a]
      theta_log(a, b) = theta_log(b, a) = half_log_divided(c[a], c[b]);
      theta_w(a, b) = theta_w(b, a) = inverse_sqrt_divided(c[a], c[b]);
    }
}

Eigen::Matrix3d from_voigt(const Vector6& s) {
  Eigen::Matrix3d m;
  m << s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2];
  return m;
}

Vector6 to_voigt_strain(const Eigen::Matrix3d& e) {  // engineering shears
  Vector6 v;
  v << e(0, 0), e(1, 1), e(2, 2), e(1, 2) + e(2, 1), e(0, 2) + e(2, 0), e(0, 1) + e(1, 0);
  return v;
}

// Plane strain (F = diag(F2, 1)): C = diag(C2, 1), so Q = diag(Q2, 1) with Q2 the rotation to
// C2's eigenvectors in closed form (no iterative 3 × 3 solver), and every in-plane direction dC
// stays in the 2 × 2 block (docs/segment.md §"Cost (knobs)").
struct PlaneSpectrum {
  Eigen::Matrix2d Q;  // columns: eigenvectors of C2
  Eigen::Vector2d c;  // eigenvalues, c[0] ≥ c[1] > 0
};

PlaneSpectrum plane_spectrum(const Eigen::Matrix2d& F2) {
  const Eigen::Matrix2d C2 = F2.transpose() * F2;
  const double mean = 0.5 * (C2(0, 0) + C2(1, 1)), half_gap = 0.5 * (C2(0, 0) - C2(1, 1));
  const double radius = std::sqrt(half_gap * half_gap + C2(0, 1) * C2(0, 1));  // C2's entries are O(1)
  PlaneSpectrum s;
  const double J = F2.determinant();
  s.c << mean + radius, J * J / (mean + radius);  // c0 c1 = det C2 = J²: no cancellation in c1
  // Eigenvector (cos φ, sin φ) of c0 with cos 2φ = half_gap/radius, sin 2φ = C2(0, 1)/radius, by
  // half-angle formulas from whichever of cos φ, sin φ is ≥ 1/√2 (no trigonometric calls).
  double cs = 1.0, sn = 0.0;
  if (radius > 0.0) {
    const double cos2 = half_gap / radius, sin2 = C2(0, 1) / radius;
    if (cos2 >= 0.0) cs = std::sqrt(0.5 * (1.0 + cos2)), sn = 0.5 * sin2 / cs;
    else sn = std::sqrt(0.5 * (1.0 - cos2)), cs = 0.5 * sin2 / sn;
  }
  s.Q << cs, -sn, sn, cs;
  return s;
}

Eigen::Matrix3d padded(const Eigen::Matrix2d& m, double corner) {
  Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
  p.topLeftCorner<2, 2>() = m;
  p(2, 2) = corner;
  return p;
}

// first_piola for F = diag(F2, 1) and the in-plane columns (or none): the same equations with the
// spectral derivatives on the 2 × 2 block (Q2ᵀ dC2 Q2 = a bᵀ + b aᵀ, a = Q2ᵀ F2ᵀ e_k, b = Q2ᵀ e_L).
FirstPiolaResult plane_first_piola(const MaterialPoint& point, const double* state_n, const Eigen::Matrix3d& F,
                                   double dt_s, double temperature_C, double* state_next, bool tangent) {
  const Eigen::Matrix2d F2 = F.topLeftCorner<2, 2>();
  const PlaneSpectrum s = plane_spectrum(F2);
  if (!(s.c[1] > 0.0)) throw core::NumericalError("material point: C not positive definite");
  const Eigen::Vector2d half_log_c(0.5 * std::log(s.c[0]), 0.5 * std::log(s.c[1]));
  const Eigen::Matrix2d lnU2 = s.Q * half_log_c.asDiagonal() * s.Q.transpose();
  const Eigen::Matrix2d W2 = s.Q * s.c.array().rsqrt().matrix().asDiagonal() * s.Q.transpose();
  Vector6 strain;
  strain << lnU2(0, 0), lnU2(1, 1), 0.0, 0.0, 0.0, 2.0 * lnU2(0, 1);

  FirstPiolaResult out;
  Matrix6 D;
  const auto* in_plane = tangent ? dynamic_cast<const InPlaneTangent*>(&point) : nullptr;  // only columns 0, 1, 5 are read
  out.stress_unrotated = in_plane ? in_plane->update_in_plane(state_n, strain, dt_s, temperature_C, state_next, D)
                                  : point.update(state_n, strain, dt_s, temperature_C, state_next, tangent ? &D : nullptr);
  const Eigen::Matrix3d tau = from_voigt(out.stress_unrotated), W = padded(W2, 1.0);
  const Eigen::Matrix3d S = W * (tau * W);
  out.P = F * S;
  out.dP_dF.setZero();
  if (!tangent) return out;

  Eigen::Matrix2d theta_log, theta_w;
  divided_differences(s.c, theta_log, theta_w);
  // dS = dW τ W + W dτ W + W τ dW by blocks (W = diag(W2, 1), dW = diag(dW2, 0), F = diag(F2, 1);
  // t = τ(0:1, 2)): the same products as on the padded 3 × 3 matrices without their zeros.
  const Eigen::Matrix2d tau2 = tau.topLeftCorner<2, 2>(), W2_tau2 = W2 * tau2, tau2_W2 = tau2 * W2;
  const Eigen::Vector2d t = tau.block<2, 1>(0, 2);
  for (int k = 0; k < 2; ++k)
    for (int L = 0; L < 2; ++L) {
      const Eigen::Vector2d a = s.Q.transpose() * F2.row(k).transpose(), b = s.Q.row(L).transpose();
      const Eigen::Matrix2d M = a * b.transpose() + b * a.transpose();
      const Eigen::Matrix2d dlnU2 = s.Q * theta_log.cwiseProduct(M) * s.Q.transpose();
      const Eigen::Matrix2d dW2 = s.Q * theta_w.cwiseProduct(M) * s.Q.transpose();
      const Vector6 dtau_v = D.col(0) * dlnU2(0, 0) + D.col(1) * dlnU2(1, 1) + D.col(5) * (2.0 * dlnU2(0, 1));
      const Eigen::Matrix3d dtau = from_voigt(dtau_v);
      const Eigen::Matrix2d dtau2 = dtau.topLeftCorner<2, 2>();
      const Eigen::Vector2d dt = dtau.block<2, 1>(0, 2);
      Eigen::Matrix3d dS;
      dS.topLeftCorner<2, 2>() = dW2 * tau2_W2 + W2 * dtau2 * W2 + W2_tau2 * dW2;
      dS.block<2, 1>(0, 2) = dW2 * t + W2 * dt;
      dS.block<1, 2>(2, 0) = dt.transpose() * W2 + t.transpose() * dW2;
      dS(2, 2) = dtau(2, 2);
      Eigen::Matrix3d dP = dS;
      dP.topRows<2>() = F2 * dS.topRows<2>();
      dP.row(k) += S.row(L);  // dF S with dF = e_k e_Lᵀ
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J) out.dP_dF(3 * i + J, 3 * k + L) = dP(i, J);
    }
  return out;
}

bool plane_strain(const Eigen::Matrix3d& F) {
  return F(0, 2) == 0.0 && F(1, 2) == 0.0 && F(2, 0) == 0.0 && F(2, 1) == 0.0 && F(2, 2) == 1.0;
}

}  // namespace

Eigen::Matrix3d spectral_derivative(const Eigen::Matrix3d& Q, const Eigen::Matrix3d& theta,
                                    const Eigen::Matrix3d& dC) {
  const Eigen::Matrix3d inner = theta.cwiseProduct(Q.transpose() * dC * Q);
  return Q * inner * Q.transpose();
}

FirstPiolaResult first_piola(const MaterialPoint& point, const double* state_n, const Eigen::Matrix3d& F,
                             double dt_s, double temperature_C, double* state_next, TangentColumns columns) {
  if (!(F.determinant() > 0.0))
    throw core::NumericalError("material point: deformation gradient with det F ≤ 0");
  if (columns != TangentColumns::all && plane_strain(F))
    return plane_first_piola(point, state_n, F, dt_s, temperature_C, state_next, columns == TangentColumns::in_plane);
  const Eigen::Matrix3d C = F.transpose() * F;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(C);
  const Eigen::Vector3d c = eig.eigenvalues();
  const Eigen::Matrix3d& Q = eig.eigenvectors();
  if (!(c.minCoeff() > 0.0)) throw core::NumericalError("material point: C not positive definite");
  const Eigen::Vector3d half_log_c = 0.5 * c.array().log().matrix();
  const Eigen::Vector3d inv_sqrt_c = c.array().rsqrt().matrix();
  const Eigen::Matrix3d lnU = Q * half_log_c.asDiagonal() * Q.transpose();
  const Eigen::Matrix3d W = Q * inv_sqrt_c.asDiagonal() * Q.transpose();  // U⁻¹

  FirstPiolaResult out;
  Matrix6 D;
  const bool tangent = columns != TangentColumns::none;
  out.stress_unrotated = point.update(state_n, to_voigt_strain(lnU), dt_s, temperature_C, state_next, tangent ? &D : nullptr);
  const Eigen::Matrix3d tau = from_voigt(out.stress_unrotated);
  const Eigen::Matrix3d S = W * tau * W;
  out.P = F * S;
  out.dP_dF.setZero();
  if (!tangent) return out;

  Eigen::Matrix3d theta_log, theta_w;
  divided_differences(c, theta_log, theta_w);
  for (int k = 0; k < 3; ++k)
    for (int L = 0; L < 3; ++L) {
      if (columns == TangentColumns::in_plane && (k == 2 || L == 2)) continue;
      const Eigen::Matrix3d dCk = F.row(k).transpose() * Eigen::RowVector3d::Unit(L);  // FᵀdF, dF = e_k e_Lᵀ
      const Eigen::Matrix3d dC = dCk + dCk.transpose();
      const Eigen::Matrix3d dlnU = spectral_derivative(Q, theta_log, dC);
      const Eigen::Matrix3d dW = spectral_derivative(Q, theta_w, dC);
      const Eigen::Matrix3d dtau = from_voigt(D * to_voigt_strain(dlnU));
      const Eigen::Matrix3d dS = dW * tau * W + W * dtau * W + W * tau * dW;
      Eigen::Matrix3d dP = F * dS;
      dP.row(k) += S.row(L);  // dF S with dF = e_k e_Lᵀ
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J) out.dP_dF(3 * i + J, 3 * k + L) = dP(i, J);
    }
  return out;
}

}  // namespace fitlib::model
