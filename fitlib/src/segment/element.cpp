#include "element.hpp"

#include <cmath>

#include <Eigen/LU>

#include "fitlib/core/error.hpp"

namespace fitlib::segment::detail {

std::vector<double> gauss_abscissae(int n) {
  if (n == 2) return {-1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)};
  return {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
}

std::vector<GaussPoint> gauss_rule(int n) {
  const std::vector<double> x = gauss_abscissae(n);
  const std::vector<double> w = n == 2 ? std::vector<double>{1.0, 1.0} : std::vector<double>{5.0 / 9, 8.0 / 9, 5.0 / 9};
  std::vector<GaussPoint> rule;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) rule.push_back({x[i], x[j], w[i] * w[j]});
  return rule;
}

void shape(int nodes, double xi, double eta, double* N, double* dxi, double* deta) {
  static const double cx[4] = {-1, 1, 1, -1}, cy[4] = {-1, -1, 1, 1};
  if (nodes == 4) {
    for (int a = 0; a < 4; ++a) {
      N[a] = 0.25 * (1 + xi * cx[a]) * (1 + eta * cy[a]);
      dxi[a] = 0.25 * cx[a] * (1 + eta * cy[a]);
      deta[a] = 0.25 * cy[a] * (1 + xi * cx[a]);
    }
    return;
  }
  for (int a = 0; a < 4; ++a) {
    const double s = xi * cx[a], t = eta * cy[a];
    N[a] = 0.25 * (1 + s) * (1 + t) * (s + t - 1);
    dxi[a] = 0.25 * cx[a] * (1 + t) * (2 * s + t);
    deta[a] = 0.25 * cy[a] * (1 + s) * (s + 2 * t);
  }
  N[4] = 0.5 * (1 - xi * xi) * (1 - eta), dxi[4] = -xi * (1 - eta), deta[4] = -0.5 * (1 - xi * xi);
  N[5] = 0.5 * (1 + xi) * (1 - eta * eta), dxi[5] = 0.5 * (1 - eta * eta), deta[5] = -(1 + xi) * eta;
  N[6] = 0.5 * (1 - xi * xi) * (1 + eta), dxi[6] = -xi * (1 + eta), deta[6] = 0.5 * (1 - xi * xi);
  N[7] = 0.5 * (1 - xi) * (1 - eta * eta), dxi[7] = -0.5 * (1 - eta * eta), deta[7] = -(1 - xi) * eta;
}

namespace {
// ∂N/∂X at a Gauss point and the reference volume element; false when the map is inverted.
bool reference_gradients(const std::vector<Eigen::Vector2d>& X, const GaussPoint& g, double* N,
                         Eigen::Matrix<double, 8, 2>& G, double& dV) {
  const int n = static_cast<int>(X.size());
  double dxi[8], deta[8];
  shape(n, g.xi, g.eta, N, dxi, deta);
  Eigen::Matrix2d J0 = Eigen::Matrix2d::Zero();
  for (int a = 0; a < n; ++a) {
    J0(0, 0) += X[a].x() * dxi[a], J0(0, 1) += X[a].x() * deta[a];
    J0(1, 0) += X[a].y() * dxi[a], J0(1, 1) += X[a].y() * deta[a];
  }
  const double detJ0 = J0.determinant();
  if (!(detJ0 > 0.0)) return false;
  const Eigen::Matrix2d J0inv = J0.inverse();
  for (int a = 0; a < n; ++a) {
    G(a, 0) = dxi[a] * J0inv(0, 0) + deta[a] * J0inv(1, 0);
    G(a, 1) = dxi[a] * J0inv(0, 1) + deta[a] * J0inv(1, 1);
  }
  dV = detJ0 * g.weight;
  return true;
}
}  // namespace

void internal_force(const std::vector<Eigen::Vector2d>& X, const std::vector<GaussPoint>& rule,
                    const std::vector<Eigen::Matrix2d>& piola, ElementVector& f) {
  const int n = static_cast<int>(X.size());
  f.setZero(2 * n);
  double N[8], dV = 0.0;
  Eigen::Matrix<double, 8, 2> G;
  for (std::size_t q = 0; q < rule.size(); ++q) {
    if (!reference_gradients(X, rule[q], N, G, dV)) continue;
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 2; ++i) f(2 * a + i) += (piola[q](i, 0) * G(a, 0) + piola[q](i, 1) * G(a, 1)) * dV;
  }
}

// f_aI = ∫ P_iJ ∂N_a/∂X_J dV;  K_aibk = ∫ ∂N_a/∂X_J A_iJkL ∂N_b/∂X_L dV (unit thickness).
bool element_response(const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& u,
                      const PlaneStrainLaw& law, const std::vector<GaussPoint>& rule, const ElementStep& step,
                      ElementVector& f, ElementMatrix* K, std::vector<ElementState>* states) {
  const int n = static_cast<int>(X.size());
  f.setZero(2 * n);
  if (K) K->setZero(2 * n, 2 * n);
  if (states) states->clear();
  const std::size_t ns = law.state_size();
  double N[8], dV = 0.0;
  Eigen::Matrix<double, 8, 2> G;  // ∂N/∂X
  for (std::size_t q = 0; q < rule.size(); ++q) {
    const GaussPoint& g = rule[q];
    if (!reference_gradients(X, g, N, G, dV)) return false;
    Eigen::Matrix2d F = Eigen::Matrix2d::Identity();
    for (int a = 0; a < n; ++a) F += u[a] * G.row(a);
    const double J = F.determinant();
    if (!(J > 0.0)) return false;
    PointResponse r;
    try {
      r = law.respond(F, {step.state_n + q * ns, step.state_next + q * ns, step.dt_s, step.temperature_C, K != nullptr});
    } catch (const core::NumericalError&) {
      return false;
    }
    if (!r.P.allFinite() || !r.A.allFinite()) return false;
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 2; ++i) f(2 * a + i) += (r.P(i, 0) * G(a, 0) + r.P(i, 1) * G(a, 1)) * dV;
    if (K) {
      // H(a, 2i + k, L) = Σ_J G(a, J) A_iJkL, then K_aibk = Σ_L H G(b, L): 2 × fewer products.
      Eigen::Matrix<double, 8, 8> H;
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < 2; ++i)
          for (int k = 0; k < 2; ++k)
            for (int L = 0; L < 2; ++L)
              H(a, 4 * i + 2 * k + L) = (G(a, 0) * r.A(2 * i, 2 * k + L) + G(a, 1) * r.A(2 * i + 1, 2 * k + L)) * dV;
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < 2; ++i)
          for (int b = 0; b < n; ++b)
            for (int k = 0; k < 2; ++k)
              (*K)(2 * a + i, 2 * b + k) += H(a, 4 * i + 2 * k) * G(b, 0) + H(a, 4 * i + 2 * k + 1) * G(b, 1);
    }
    if (states) {
      Eigen::Vector2d Xg = Eigen::Vector2d::Zero();
      for (int a = 0; a < n; ++a) Xg += N[a] * X[a];
      states->push_back({r.P * F.transpose() / J, r.sigma33_MPa, Xg, r.P, F});
    }
  }
  return true;
}

// f_a = −p ∫ N_a (t_y, −t_x) dξ with t = Σ x_b dN_b/dξ, the outward normal times ds.
void pressure_load(const std::vector<Eigen::Vector2d>& x, double p, ElementVector& f, ElementMatrix& D) {
  const int n = static_cast<int>(x.size());
  f.setZero(2 * n);
  D.setZero(2 * n, 2 * n);
  const std::vector<double> pts = gauss_abscissae(3);
  const double w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  for (int q = 0; q < 3; ++q) {
    const double s = pts[q];
    double N[3], dN[3];
    if (n == 2) {
      N[0] = 0.5 * (1 - s), N[1] = 0.5 * (1 + s), dN[0] = -0.5, dN[1] = 0.5;
    } else {
      N[0] = 0.5 * s * (s - 1), N[1] = 0.5 * s * (s + 1), N[2] = 1 - s * s;
      dN[0] = s - 0.5, dN[1] = s + 0.5, dN[2] = -2 * s;
    }
    Eigen::Vector2d t = Eigen::Vector2d::Zero();
    for (int b = 0; b < n; ++b) t += x[b] * dN[b];
    for (int a = 0; a < n; ++a) {
      f(2 * a) += -p * N[a] * t.y() * w[q];
      f(2 * a + 1) += p * N[a] * t.x() * w[q];
      for (int b = 0; b < n; ++b) {
        D(2 * a, 2 * b + 1) += -p * N[a] * dN[b] * w[q];
        D(2 * a + 1, 2 * b) += p * N[a] * dN[b] * w[q];
      }
    }
  }
}

}  // namespace fitlib::segment::detail
