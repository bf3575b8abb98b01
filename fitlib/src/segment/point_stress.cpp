// Stresses at points and section forces of a solved segment (fitlib/segment/solver.hpp): a point
// located in its element(s), its stress interpolated from the integration points and averaged over
// the elements of its role that share it; the internal force through a cut.
#include <cmath>
#include <sstream>

#include <Eigen/LU>

#include "element.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/segment/solver.hpp"

namespace fitlib::segment {

SectionForce section_force(const StaticProblem& p, const StaticSolution& s, double x_cut,
                           const Eigen::Vector2d& about, Integration integration) {
  const Mesh& m = *p.mesh;
  const auto rule = detail::gauss_rule(gauss_order(m, integration));
  const int npe = m.nodes_per_element;
  const double tol = 1e-9 * (1.0 + m.half_length_mm);
  std::vector<Eigen::Vector2d> X(npe), u(npe);
  detail::ElementVector f;
  SectionForce out;
  for (int e = 0; e < m.element_count(); ++e) {
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (int a = 0; a < 4; ++a) centroid += 0.25 * m.X[m.elements[e][a]];
    if (centroid.x() >= x_cut) continue;
    bool touches = false;
    for (int a = 0; a < npe; ++a) {
      X[a] = m.X[m.elements[e][a]];
      u[a] = s.u_mm[m.elements[e][a]];
      touches = touches || std::abs(X[a].x() - x_cut) < tol;
    }
    if (!touches) continue;
    std::vector<Eigen::Matrix2d> piola;
    for (const IntegrationPointStress& q : s.points[e]) piola.push_back(q.piola_MPa);
    detail::internal_force(X, rule, piola, f);
    for (int a = 0; a < npe; ++a) {
      if (std::abs(X[a].x() - x_cut) >= tol) continue;
      const Eigen::Vector2d fa = f.segment<2>(2 * a), x = X[a] + u[a] - about;
      out.force_N_mm += fa;
      out.moment_N += x.y() * fa.x() - x.x() * fa.y();
    }
  }
  return out;
}

namespace {

// P's isoparametric coordinates in element e by Newton on its reference map; false if P is not in it.
bool inverse_map(const Mesh& m, int e, const Eigen::Vector2d& P, Eigen::Vector2d& xi) {
  const int npe = m.nodes_per_element;
  double N[8], dxi[8], deta[8];
  Eigen::Vector2d lo = m.X[m.elements[e][0]], hi = lo;
  for (int a = 0; a < npe; ++a) lo = lo.cwiseMin(m.X[m.elements[e][a]]), hi = hi.cwiseMax(m.X[m.elements[e][a]]);
  const double pad = 1e-9 * (1.0 + (hi - lo).norm());
  if ((P.array() < lo.array() - pad).any() || (P.array() > hi.array() + pad).any()) return false;
  xi.setZero();
  for (int it = 0; it < 30; ++it) {
    detail::shape(npe, xi.x(), xi.y(), N, dxi, deta);
    Eigen::Vector2d x = Eigen::Vector2d::Zero();
    Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
    for (int a = 0; a < npe; ++a) {
      const Eigen::Vector2d& Xa = m.X[m.elements[e][a]];
      x += N[a] * Xa;
      J.col(0) += dxi[a] * Xa, J.col(1) += deta[a] * Xa;
    }
    xi += J.inverse() * (P - x);
  }
  return xi.allFinite() && xi.cwiseAbs().maxCoeff() <= 1.0 + 1e-7;
}

void add_scaled(IntegrationPointStress& out, const IntegrationPointStress& q, double w) {
  out.cauchy_MPa += w * q.cauchy_MPa, out.sigma33_MPa += w * q.sigma33_MPa;
  out.piola_MPa += w * q.piola_MPa, out.F += w * q.F;
}

// One element's integration-point values at `at` by the Lagrange polynomials through the Gauss
// abscissae g.
IntegrationPointStress interpolate_in(const StaticSolution& s, const ElementPoint& at, const std::vector<double>& g,
                                      const Eigen::Vector2d& X) {
  const int n = static_cast<int>(g.size());
  auto lagrange = [&](int i, double t) {
    double v = 1.0;
    for (int j = 0; j < n; ++j)
      if (j != i) v *= (t - g[j]) / (g[i] - g[j]);
    return v;
  };
  IntegrationPointStress out{X, Eigen::Matrix2d::Zero(), 0.0, Eigen::Matrix2d::Zero(), Eigen::Matrix2d::Zero()};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      add_scaled(out, s.points[at.element][j * n + i], lagrange(i, at.xi.x()) * lagrange(j, at.xi.y()));
  return out;
}

}  // namespace

PointLocation locate(const Mesh& m, const Eigen::Vector2d& P) {
  PointLocation out;
  Eigen::Vector2d xi;
  for (int e = 0; e < m.element_count(); ++e) {
    if (!inverse_map(m, e, P, xi)) continue;
    if (out.element < 0) out.element = e, out.xi = xi;
    else if (m.roles[e] == m.roles[out.element]) out.shared.push_back({e, xi});
  }
  if (out.element >= 0) return out;
  std::ostringstream msg;
  msg << "point (" << P.x() << ", " << P.y() << ") mm is outside the segment mesh";
  throw core::InputError(msg.str());
}

IntegrationPointStress interpolate(const StaticSolution& s, const PointLocation& at, int n, const Eigen::Vector2d& X) {
  const std::vector<double> g = detail::gauss_abscissae(n);
  IntegrationPointStress out = interpolate_in(s, {at.element, at.xi}, g, X);
  for (const ElementPoint& other : at.shared) add_scaled(out, interpolate_in(s, other, g, X), 1.0);
  const double w = 1.0 / (1.0 + static_cast<double>(at.shared.size()));
  out.cauchy_MPa *= w, out.sigma33_MPa *= w, out.piola_MPa *= w, out.F *= w;
  return out;
}

Eigen::Matrix2d stress_at(const Mesh& m, const StaticSolution& s, const Eigen::Vector2d& P,
                          Integration integration, double* sigma33) {
  const IntegrationPointStress q = interpolate(s, locate(m, P), gauss_order(m, integration), P);
  if (sigma33) *sigma33 = q.sigma33_MPa;
  return q.cauchy_MPa;
}

}  // namespace fitlib::segment
