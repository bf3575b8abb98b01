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

double flank_stick_stiffness_N_mm4(double shear_modulus_MPa, double width_mm) {
  return 12.0 * shear_modulus_MPa / (width_mm * width_mm);
}

FlankStickPoint flank_stick_point(double w, double slip, double k_t, double limit) {
  FlankStickPoint p;
  p.slip_after_mm = w;  // no stick: the slip follows the point
  if (!(k_t > 0.0) || !(limit > 0.0)) return p;
  const double trial = -k_t * (w - slip);
  p.slipping = std::abs(trial) > limit;
  p.B_t_N_mm3 = p.slipping ? std::copysign(limit, trial) : trial;
  p.dB_dw_N_mm4 = p.slipping ? 0.0 : -k_t;
  p.slip_after_mm = w + p.B_t_N_mm3 / k_t;  // −k_t (w − w_s) = B_t
  return p;
}

FlankSlidePoint flank_slide_point(const Eigen::Vector2d& u_dot, const Eigen::Vector2d& friction, double V, double V0) {
  FlankSlidePoint p;
  const double F = friction.norm();
  if (!(F > 0.0) || !(V > 0.0) || !(V0 > 0.0)) return p;
  const Eigen::Vector2d e = -friction / F;  // ê = −friction / F (Report I's 6.6–6.7)
  auto g = [V0](const Eigen::Vector2d& v) { return Eigen::Vector2d(v / std::sqrt(v.squaredNorm() + V0 * V0)); };
  const Eigen::Vector2d v = V * e + u_dot;
  const double q = v.squaredNorm() + V0 * V0;
  if (!u_dot.isZero(0.0)) p.b_lr_N_mm3 = -F * (g(v) - g(V * e));  // exactly Report I's without motion
  p.db_dv_lr = -F / (q * std::sqrt(q)) * (q * Eigen::Matrix2d::Identity() - v * v.transpose());
  return p;
}

namespace {

// What the flank keeps: per element and integration point (rule order) the path position, the
// reference depth and the committed slip; at the prepared λ the cord curve, its interval starts,
// the levels per element, each point's expected foot and (stick, turn) its column's cord point and
// tangent.
struct FlankState {
  int points = 0;  // per element
  bool stick = false, slide = false, history = false;  // history: either; frames at every λ, offsets committed
  std::vector<double> path_x, reference_depth, slip;
  std::vector<double> committed_offset, next_offset;  // along the cord from the column's cord point
  std::vector<double> next_slip;
  double committed_time_s = 0.0, next_time_s = 0.0, dt_s = 0.0;
  bool pending = false;  // committed into next_*, taken at the next prepare
  std::function<NeutralCurve(double)> curve_at;
  std::function<void(double, FlankLevels&)> levels_at;
  std::optional<NeutralCurve> curve;
  CurveStarts starts;
  FlankLevels levels;
  std::vector<double> s_hint;
  std::vector<Eigen::Vector2d> cord, tangent;

  bool radial(int e) const { return levels.radial_N_mm4[e] > 0.0; }
  bool sticks(int e) const { return levels.stick_N_mm4[e] > 0.0 && levels.stick_limit_N_mm3[e] > 0.0; }
  bool slides(int e) const { return levels.slide_mm_s[e] > 0.0 && dt_s > 0.0 && !levels.friction_lr_N_mm3[e].isZero(0.0); }
  double offset(std::size_t i, const Eigen::Vector2d& x) const { return tangent[i].dot(x - cord[i]); }
  Eigen::Vector2d normal(std::size_t i) const { return {-tangent[i].y(), tangent[i].x()}; }  // (sin φ, cos φ)
};

}  // namespace

StaticProblem::FollowingForce flank_contact(const Mesh& m, const std::vector<double>& path_x_mm, Integration integration,
                                            const NeutralCurve& reference_curve,
                                            std::function<NeutralCurve(double)> curve_at, bool stick, bool slide,
                                            std::function<void(double, FlankLevels&)> levels) {
  auto st = std::make_shared<FlankState>();
  const bool history = stick || slide;
  const auto rule = detail::gauss_rule(gauss_order(m, integration));
  const int npe = m.nodes_per_element;
  st->points = static_cast<int>(rule.size());
  st->stick = stick, st->slide = slide, st->history = history;
  double N[8], dxi[8], deta[8];
  std::vector<Eigen::Vector2d> reference;  // each point's reference position
  for (int e = 0; e < m.element_count(); ++e)
    for (const auto& g : rule) {
      detail::shape(npe, g.xi, g.eta, N, dxi, deta);
      Eigen::Vector2d X = Eigen::Vector2d::Zero();
      double x = 0.0;
      for (int a = 0; a < npe; ++a) X += N[a] * m.X[m.elements[e][a]], x += N[a] * path_x_mm[m.elements[e][a]];
      st->path_x.push_back(x);
      st->reference_depth.push_back(reference_curve.coordinates(X.x(), X.y()).h_mm);
      reference.push_back(X);
    }
  st->curve_at = std::move(curve_at);
  st->levels_at = std::move(levels);
  const std::size_t n = st->path_x.size(), elements = static_cast<std::size_t>(m.element_count());
  for (auto* v : {&st->levels.radial_N_mm4, &st->levels.stick_N_mm4, &st->levels.stick_limit_N_mm3, &st->levels.slide_mm_s})
    v->assign(elements, 0.0);
  st->levels.friction_lr_N_mm3.assign(elements, Eigen::Vector2d::Zero());
  st->s_hint.assign(n, 0.0);
  if (history) {
    st->cord.assign(n, Eigen::Vector2d::Zero()), st->tangent.assign(n, Eigen::Vector2d::Zero());
    // The offsets start from the reference's on the curve at λ = 0 (no motion before the first commit).
    const NeutralCurve start = st->curve_at(0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const CurvePoint c = start.at(start.s_from_unstrained(st->path_x[i]));
      const Eigen::Vector2d t(std::cos(c.phi_rad), -std::sin(c.phi_rad));
      st->committed_offset.push_back(t.dot(reference[i] - Eigen::Vector2d(c.x_mm, c.y_mm)));
      st->slip.push_back(st->committed_offset.back());
    }
    st->next_offset = st->committed_offset, st->next_slip = st->slip;
  }
  StaticProblem::FollowingForce f;
  f.symmetric = !slide;
  f.prepare = [st](double lambda) {
    if (st->pending) {  // the commit takes effect at the next level (a snapshot at the committed one sees the step's force)
      st->committed_offset.swap(st->next_offset), st->slip.swap(st->next_slip);
      st->committed_time_s = st->next_time_s, st->pending = false;
    }
    st->levels_at(lambda, st->levels);
    st->dt_s = st->levels.time_s - st->committed_time_s;
    const auto& k = st->levels.radial_N_mm4;
    const bool radial = std::any_of(k.begin(), k.end(), [](double v) { return v > 0.0; });
    if (!radial && !st->history) return;
    st->curve.emplace(st->curve_at(lambda));
    if (radial) st->starts = st->curve->starts();
    for (std::size_t e = 0; e < k.size(); ++e)
      for (int g = 0; g < st->points; ++g) {
        const std::size_t i = e * st->points + g;
        if (!st->radial(static_cast<int>(e)) && !st->history) continue;
        const double s = st->curve->s_from_unstrained(st->path_x[i]);
        if (st->radial(static_cast<int>(e))) st->s_hint[i] = s;
        if (!st->history) continue;
        const CurvePoint c = st->curve->at(s);  // the column's cord point: the foot the stick holds to
        st->cord[i] = {c.x_mm, c.y_mm}, st->tangent[i] = {std::cos(c.phi_rad), -std::sin(c.phi_rad)};
      }
  };
  f.at = [st](int e, int g, const Eigen::Vector2d& x, Eigen::Vector2d& b, Eigen::Matrix2d& db) {
    const bool radial = st->radial(e), sticks = st->stick && st->sticks(e), slides = st->slide && st->slides(e);
    if (!radial && !sticks && !slides) return false;
    const std::size_t i = static_cast<std::size_t>(e) * st->points + g;
    if (radial) {
      const FlankFoundationPoint p = flank_foundation_point(st->curve->coordinates(x.x(), x.y(), st->starts, st->s_hint[i]),
                                                            st->reference_depth[i], st->levels.radial_N_mm4[e]);
      b = p.b_N_mm3, db = p.db_dx_N_mm4;
    } else {
      b.setZero(), db.setZero();
    }
    if (sticks) {  // B_t t with ∂w/∂x = t (the frame is fixed at λ)
      const FlankStickPoint p = flank_stick_point(st->offset(i, x), st->slip[i], st->levels.stick_N_mm4[e],
                                                  st->levels.stick_limit_N_mm3[e]);
      b += p.B_t_N_mm3 * st->tangent[i];
      db += p.dB_dw_N_mm4 * st->tangent[i] * st->tangent[i].transpose();
    }
    if (slides) {  // u̇ = ((w − w_n) / Δt, 0): only the motion along the belt is beyond Report I's sliding
      Eigen::Matrix2d Q;
      Q.col(0) = st->tangent[i], Q.col(1) = st->normal(i);
      const FlankSlidePoint p = flank_slide_point(Eigen::Vector2d((st->offset(i, x) - st->committed_offset[i]) / st->dt_s, 0.0),
                                                  st->levels.friction_lr_N_mm3[e], st->levels.slide_mm_s[e],
                                                  st->levels.slide_floor_mm_s);
      b += Q * p.b_lr_N_mm3;
      db += Q * p.db_dv_lr.col(0) * st->tangent[i].transpose() / st->dt_s;  // ∂u̇/∂x = (tᵀ/Δt, 0): unsymmetric
    }
    return true;
  };
  if (history)
    f.commit = [st](int e, int g, const Eigen::Vector2d& x) {
      const std::size_t i = static_cast<std::size_t>(e) * st->points + g;
      st->next_offset[i] = st->offset(i, x);
      st->next_time_s = st->levels.time_s;
      st->next_slip[i] = flank_stick_point(st->offset(i, x), st->slip[i], st->stick && st->sticks(e) ? st->levels.stick_N_mm4[e] : 0.0,
                                           st->levels.stick_limit_N_mm3[e])
                             .slip_after_mm;
      st->pending = true;
    };
  return f;
}

StaticProblem::FollowingForce flank_foundation(const Mesh& m, const std::vector<double>& path_x_mm,
                                               Integration integration, const NeutralCurve& reference_curve,
                                               std::function<NeutralCurve(double)> curve_at,
                                               std::function<void(double, std::vector<double>&)> stiffness) {
  return flank_contact(m, path_x_mm, integration, reference_curve, std::move(curve_at), false, false,
                       [stiffness = std::move(stiffness)](double lambda, FlankLevels& levels) {
                         stiffness(lambda, levels.radial_N_mm4);
                       });
}

}  // namespace fitlib::segment
