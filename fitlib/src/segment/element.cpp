#include "element.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "fitlib/core/error.hpp"
#include "fitlib/segment/solver.hpp"

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

// One integration point's kinematics: ∂N/∂X, dV, F and J = det F; false when inverted.
struct PointKinematics {
  double N[8];
  Eigen::Matrix<double, 8, 2> G;
  double dV = 0.0, J = 0.0;
  Eigen::Matrix2d F;
};

// ∂N/∂X, N and dV from the element's cached reference point, or computed when there is none.
bool reference_of(const std::vector<Eigen::Vector2d>& X, const GaussPoint& g, const ReferencePoint* cached,
                  PointKinematics& k) {
  if (!cached) return reference_gradients(X, g, k.N, k.G, k.dV);
  std::copy(cached->N, cached->N + 8, k.N);
  k.G = cached->G;
  k.dV = cached->dV;
  return cached->ok;
}

bool point_kinematics(const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& u,
                      const GaussPoint& g, PointKinematics& k, const ReferencePoint* cached = nullptr) {
  if (!reference_of(X, g, cached, k)) return false;
  k.F.setIdentity();
  for (std::size_t a = 0; a < X.size(); ++a) k.F += u[a] * k.G.row(static_cast<int>(a));
  k.J = k.F.determinant();
  return k.J > 0.0;
}

// d(ln J)/du: ∂J/∂u_bk = J (F⁻ᵀ)_kL ∂N_b/∂X_L.
ElementVector dlnJ_du(const PointKinematics& k, int n) {
  const Eigen::Matrix2d FinvT = k.F.inverse().transpose();
  ElementVector d(2 * n);
  for (int b = 0; b < n; ++b) d.segment<2>(2 * b) = FinvT * k.G.row(b).transpose();
  return d;
}

// F-bar's volume field (docs/segment.md §Element choice): J at the reduced points (2×2 for
// 8 nodes, the centre for 4) and d(ln J)/du there; J̄ at (ξ, η) is their bilinear interpolation.
struct VolumeField {
  std::vector<GaussPoint> points;
  std::vector<double> J;
  std::vector<ElementVector> dlnJ;
};

bool volume_field(const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& u, VolumeField& v) {
  const int n = static_cast<int>(X.size());
  v.points = n == 8 ? gauss_rule(2) : std::vector<GaussPoint>{{0.0, 0.0, 4.0}};
  PointKinematics k;
  for (const GaussPoint& g : v.points) {
    if (!point_kinematics(X, u, g, k)) return false;
    v.J.push_back(k.J);
    v.dlnJ.push_back(dlnJ_du(k, n));
  }
  return true;
}

// J̄ at (ξ, η) and d(ln J̄)/du; false when the interpolated volume is not positive.
bool interpolated_volume(const VolumeField& v, double xi, double eta, double& Jbar, ElementVector& dlnJbar) {
  Jbar = 0.0;
  dlnJbar.setZero(v.dlnJ.front().size());
  for (std::size_t m = 0; m < v.points.size(); ++m) {
    // Bilinear Lagrange weight of the point at (±1/√3, ±1/√3): ¼ (1 + 3 ξ ξ_m)(1 + 3 η η_m).
    const double w = v.points.size() == 1 ? 1.0 : 0.25 * (1 + 3 * xi * v.points[m].xi) * (1 + 3 * eta * v.points[m].eta);
    Jbar += w * v.J[m];
    dlnJbar += w * v.J[m] * v.dlnJ[m];
  }
  if (!(Jbar > 0.0)) return false;
  dlnJbar /= Jbar;
  return true;
}

void add_force(const PointKinematics& k, const Eigen::Matrix2d& P, int n, ElementVector& f) {
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < 2; ++i) f(2 * a + i) += (P(i, 0) * k.G(a, 0) + P(i, 1) * k.G(a, 1)) * k.dV;
}

// K_aibk += ∫ ∂N_a/∂X_J A_iJkL ∂N_b/∂X_L dV, as K(:, 2b + k) += Σ_L H(:, 2k + L) ∂N_b/∂X_L with
// H(2a + i, 2k + L) = Σ_J ∂N_a/∂X_J A_iJkL dV: whole contiguous columns (vectorised) at a time.
void add_material_stiffness(const PointKinematics& k, const Eigen::Matrix4d& A, int n, ElementMatrix& K) {
  const auto& G = k.G;
  Eigen::Matrix<double, 16, 4> H;
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < 2; ++i) H.row(2 * a + i) = (G(a, 0) * A.row(2 * i) + G(a, 1) * A.row(2 * i + 1)) * k.dV;
  const int m = 2 * n;
  for (int b = 0; b < n; ++b)
    for (int c = 0; c < 2; ++c)
      K.col(2 * b + c).head(m) += H.col(2 * c).head(m) * G(b, 0) + H.col(2 * c + 1).head(m) * G(b, 1);
}

// F-bar's extra tangent: with P_eff = P(F̄)/α, α = (J̄/J)^½, F̄ = α F,
// dP_eff = A:dF + (A:F − P_eff) ½ (dJ̄/J̄ − dJ/J)  (docs/segment.md §Element choice).
void add_volume_stiffness(const PointKinematics& k, const Eigen::Matrix4d& A, const Eigen::Matrix2d& P_eff,
                          const ElementVector& dlnJbar, const ElementVector& dlnJ, int n, ElementMatrix& K) {
  Eigen::Matrix2d Q = -P_eff;
  for (int i = 0; i < 2; ++i)
    for (int J = 0; J < 2; ++J)
      for (int c = 0; c < 2; ++c)
        for (int L = 0; L < 2; ++L) Q(i, J) += A(2 * i + J, 2 * c + L) * k.F(c, L);
  ElementVector v = ElementVector::Zero(2 * n);
  add_force(k, Q, n, v);
  K.noalias() += v * (0.5 * (dlnJbar - dlnJ)).transpose();
}

// Newton on the mixed form (u and a pressure p per point, p condensed out) has the displacement
// form's residual and tangent except the tangent's pressure term, which it takes at the pressure
// linearised over the last step, p̂ − κ det ΔF (in 2-D det(F_last + ΔF) = det F_last + cof F_last : ΔF
// + det ΔF), instead of at the new iterate's p̂: near incompressibility κ det ΔF is a large spurious
// pressure that turns the next step (docs/segment.md §"Cost (reference)", 2026-12-04). κ is the
// tangent's own in-plane bulk stiffness cof:A:cof / (cof:cof)²; the pressure term is δp ∂cof/∂F, a
// constant in 2-D. The residual is unchanged, so is the solution.
Eigen::Matrix4d linearised_pressure_tangent(const Eigen::Matrix4d& A, const Eigen::Matrix2d& F, const Eigen::Matrix2d& F_last) {
  const Eigen::Vector4d cof(F(1, 1), -F(1, 0), -F(0, 1), F(0, 0));  // J F⁻ᵀ, components 2i + J
  const double kappa = cof.dot(A * cof) / (cof.squaredNorm() * cof.squaredNorm());
  const double dp = -kappa * (F - F_last).determinant();
  Eigen::Matrix4d out = A;
  out(0, 3) += dp, out(3, 0) += dp, out(1, 2) -= dp, out(2, 1) -= dp;
  return out;
}

PointResponse respond(const PlaneStrainLaw& law, const Eigen::Matrix2d& F, const ElementStep& step, std::size_t q,
                      bool tangent, bool& ok) {
  const std::size_t ns = law.state_size();
  PointResponse r;
  try {
    r = law.respond(F, {step.state_n + q * ns, step.state_next + q * ns, step.dt_s, step.temperature_C, tangent});
  } catch (const core::NumericalError&) {
    ok = false;
    return r;
  }
  ok = r.P.allFinite() && r.A.allFinite();
  return r;
}
}  // namespace

std::vector<ReferencePoint> reference_points(const std::vector<Eigen::Vector2d>& X, const std::vector<GaussPoint>& rule) {
  std::vector<ReferencePoint> out(rule.size());
  for (std::size_t q = 0; q < rule.size(); ++q) {
    ReferencePoint& r = out[q];
    std::fill(r.N, r.N + 8, 0.0);
    r.G.setZero();
    r.ok = reference_gradients(X, rule[q], r.N, r.G, r.dV);
  }
  return out;
}

void internal_force(const std::vector<Eigen::Vector2d>& X, const std::vector<GaussPoint>& rule,
                    const std::vector<Eigen::Matrix2d>& piola, ElementVector& f) {
  const int n = static_cast<int>(X.size());
  f.setZero(2 * n);
  PointKinematics k;
  for (std::size_t q = 0; q < rule.size(); ++q)
    if (reference_gradients(X, rule[q], k.N, k.G, k.dV)) add_force(k, piola[q], n, f);
}

// f_aI = ∫ P_iJ ∂N_a/∂X_J dV;  K_aibk = ∫ ∂N_a/∂X_J A_iJkL ∂N_b/∂X_L dV (unit thickness). With
// F-bar, P is the law's at F̄ divided by α (the Cauchy stress of F̄ on the current volume).
bool element_response(const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& u,
                      const PlaneStrainLaw& law, const std::vector<GaussPoint>& rule, const ElementStep& step,
                      ElementVector& f, ElementMatrix* K, std::vector<ElementState>* states, bool f_bar,
                      PressureMemory* memory, const ReferencePoint* reference) {
  const int n = static_cast<int>(X.size());
  f.setZero(2 * n);
  if (K) K->setZero(2 * n, 2 * n);
  if (states) states->clear();
  VolumeField volume;
  if (f_bar && !volume_field(X, u, volume)) return false;
  PointKinematics k;
  ElementVector dlnJbar;
  for (std::size_t q = 0; q < rule.size(); ++q) {
    if (!point_kinematics(X, u, rule[q], k, reference ? reference + q : nullptr)) return false;
    double alpha = 1.0, Jbar = k.J;
    if (f_bar) {
      if (!interpolated_volume(volume, rule[q].xi, rule[q].eta, Jbar, dlnJbar)) return false;
      alpha = std::sqrt(Jbar / k.J);
    }
    const Eigen::Matrix2d Fbar = alpha * k.F;
    bool ok = true;
    const PointResponse r = respond(law, Fbar, step, q, K != nullptr, ok);
    if (!ok) return false;
    const Eigen::Matrix2d P_eff = r.P / alpha;
    add_force(k, P_eff, n, f);
    if (K && memory && !f_bar) {
      add_material_stiffness(k, memory->follows ? linearised_pressure_tangent(r.A, k.F, memory->F_last[q]) : r.A, n, *K);
      memory->F_last[q] = k.F;
    } else if (K) {
      add_material_stiffness(k, r.A, n, *K);
    }
    if (K && f_bar) add_volume_stiffness(k, r.A, P_eff, dlnJbar, dlnJ_du(k, n), n, *K);
    if (states) {
      Eigen::Vector2d Xg = Eigen::Vector2d::Zero();
      for (int a = 0; a < n; ++a) Xg += k.N[a] * X[a];
      states->push_back({r.P * Fbar.transpose() / Jbar, r.sigma33_MPa, Xg, P_eff, Fbar});
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

namespace fitlib::segment {
// F-bar's internal force is not the gradient of an energy: its tangent is unsymmetric.
bool symmetric_tangent(Integration integration) { return integration != Integration::fbar; }

Integration integration_from_string(const std::string& name) {
  if (name == "reduced") return Integration::reduced;
  if (name == "full") return Integration::full;
  if (name == "fbar") return Integration::fbar;
  throw core::UsageError("integration must be \"reduced\", \"full\" or \"fbar\", not \"" + name + "\"");
}

const char* to_string(Integration integration) {
  return integration == Integration::reduced ? "reduced" : integration == Integration::full ? "full" : "fbar";
}
}  // namespace fitlib::segment
