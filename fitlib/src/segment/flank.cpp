// The deformation-limited flank contact (fitlib/segment/flank.hpp; docs/segment.md "Flank foundation").
#include "fitlib/segment/flank.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "element.hpp"

namespace fitlib::segment {

double flank_stiffness_N_mm4(double lateral_modulus_MPa, double wedge_half_angle_rad, double width_mm) {
  const double t = std::tan(wedge_half_angle_rad);
  return 4.0 * lateral_modulus_MPa * t * t / (width_mm * width_mm);
}

FlankFoundationPoint flank_foundation_point(const CurveCoordinates& at, double reference_depth_mm, double k) {
  const Eigen::Vector2d n(std::sin(at.phi_rad), std::cos(at.phi_rad)), t(std::cos(at.phi_rad), -std::sin(at.phi_rad));
  const double delta = at.h_mm - reference_depth_mm;
  FlankFoundationPoint p;
  p.b_N_mm3 = k * delta * n;  // −∇(½ k δ²), ∇h = −n
  // −∇∇(½ k δ²) = −k (∇h ∇hᵀ + δ ∇∇h), ∇∇h = −K t tᵀ / (1 − K h) (the depth's level lines are the
  // curve's parallels, of radius 1/K − h)
  p.db_dx_N_mm4 = -k * n * n.transpose() + k * delta * at.K_1_mm / (1.0 - at.K_1_mm * at.h_mm) * t * t.transpose();
  return p;
}

namespace {

// What the foundation keeps: per element and integration point (rule order) the path position and
// the reference depth; at the prepared λ the cord curve, its interval starts, k per element and
// each point's expected foot.
struct FlankState {
  int points = 0;  // per element
  std::vector<double> path_x, reference_depth;
  std::function<NeutralCurve(double)> curve_at;
  std::function<void(double, std::vector<double>&)> stiffness;
  std::optional<NeutralCurve> curve;
  CurveStarts starts;
  std::vector<double> k, s_hint;
};

}  // namespace

StaticProblem::FollowingForce flank_foundation(const Mesh& m, const std::vector<double>& path_x_mm,
                                               Integration integration, const NeutralCurve& reference_curve,
                                               std::function<NeutralCurve(double)> curve_at,
                                               std::function<void(double, std::vector<double>&)> stiffness) {
  auto st = std::make_shared<FlankState>();
  const auto rule = detail::gauss_rule(gauss_order(m, integration));
  const int npe = m.nodes_per_element;
  st->points = static_cast<int>(rule.size());
  double N[8], dxi[8], deta[8];
  for (int e = 0; e < m.element_count(); ++e)
    for (const auto& g : rule) {
      detail::shape(npe, g.xi, g.eta, N, dxi, deta);
      Eigen::Vector2d X = Eigen::Vector2d::Zero();
      double x = 0.0;
      for (int a = 0; a < npe; ++a) X += N[a] * m.X[m.elements[e][a]], x += N[a] * path_x_mm[m.elements[e][a]];
      st->path_x.push_back(x);
      st->reference_depth.push_back(reference_curve.coordinates(X.x(), X.y()).h_mm);
    }
  st->curve_at = std::move(curve_at);
  st->stiffness = std::move(stiffness);
  st->k.assign(m.element_count(), 0.0);
  st->s_hint.assign(st->path_x.size(), 0.0);
  StaticProblem::FollowingForce f;
  f.prepare = [st](double lambda) {
    st->stiffness(lambda, st->k);
    if (std::none_of(st->k.begin(), st->k.end(), [](double k) { return k > 0.0; })) return;
    st->curve.emplace(st->curve_at(lambda));
    st->starts = st->curve->starts();
    for (std::size_t e = 0; e < st->k.size(); ++e)
      for (int g = 0; st->k[e] > 0.0 && g < st->points; ++g) {
        const std::size_t i = e * st->points + g;
        st->s_hint[i] = st->curve->s_from_unstrained(st->path_x[i]);
      }
  };
  f.at = [st](int e, int g, const Eigen::Vector2d& x, Eigen::Vector2d& b, Eigen::Matrix2d& db) {
    if (!(st->k[e] > 0.0)) return false;
    const std::size_t i = static_cast<std::size_t>(e) * st->points + g;
    const FlankFoundationPoint p =
        flank_foundation_point(st->curve->coordinates(x.x(), x.y(), st->starts, st->s_hint[i]), st->reference_depth[i], st->k[e]);
    b = p.b_N_mm3, db = p.db_dx_N_mm4;
    return true;
  };
  return f;
}

}  // namespace fitlib::segment
