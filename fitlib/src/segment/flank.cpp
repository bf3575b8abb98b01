// The deformation-limited flank contact (fitlib/segment/flank.hpp; docs/segment.md "Flank foundation").
#include "fitlib/segment/flank.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

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

FlankTurnPoint flank_turn_point(double dw, double layer, const Eigen::Vector2d& friction, double k_t, double slide_mm) {
  FlankTurnPoint p;
  const double F = friction.norm();
  if (!(F > 0.0) || !(k_t > 0.0)) return p;
  const double c = F / (F + k_t * std::max(slide_mm, 0.0));
  p.layer_after_N_mm3 = c * (layer - k_t * dw);
  const Eigen::Vector2d q = friction + Eigen::Vector2d(p.layer_after_N_mm3, 0.0);
  const double Q = q.norm();
  if (!(Q > 1e-12 * F)) return p;  // the layer cancels the friction along the belt: no direction
  const Eigen::Vector2d n = q / Q;
  p.b_lr_N_mm3 = F * n - friction;
  p.db_dw_lr_N_mm4 = -c * k_t * F / Q * (Eigen::Vector2d(1.0, 0.0) - n.x() * n);
  return p;
}

namespace {

// The flank as a load acting at the integration points. It keeps per element and integration
// point (rule order) the path position, the reference depth and the committed slip; at the
// prepared λ the cord curve, its interval starts, the levels per element, each point's expected
// foot and (stick, turn) its column's cord point and tangent.
class FlankContact final : public Load {
 public:
  FlankContact(const Mesh& m, const std::vector<double>& path_x_mm, Integration integration,
               const NeutralCurve& reference_curve, std::function<NeutralCurve(double)> curve_at, bool stick,
               bool slide, bool turn, std::function<void(double, FlankLevels&)> levels);
  void prepare(double lambda) override;
  bool acts_at_points() const override { return true; }
  bool at_point(int e, int g, const Eigen::Vector2d& x, Eigen::Vector2d& b, Eigen::Matrix2d& db) const override;
  void commit(const ConvergedLoads& state) override;
  bool symmetric() const override { return !slide_ && !turn_; }  // the friction turns with the motion

 private:
  // The offsets start from the reference's on the curve at λ = 0 (no motion before the first commit).
  void start_offsets(const std::vector<Eigen::Vector2d>& reference);
  // Each point's expected foot on the prepared curve and (history) its column's cord frame.
  void place_feet();

  bool radial(int e) const { return levels_.radial_N_mm4[e] > 0.0; }
  bool sticks(int e) const { return levels_.stick_N_mm4[e] > 0.0 && levels_.stick_limit_N_mm3[e] > 0.0; }
  bool slides(int e) const { return levels_.slide_mm_s[e] > 0.0 && dt_s_ > 0.0 && !levels_.friction_lr_N_mm3[e].isZero(0.0); }
  bool turns(int e) const { return levels_.turn_N_mm4[e] > 0.0 && !levels_.friction_lr_N_mm3[e].isZero(0.0); }
  FlankTurnPoint turn_at(std::size_t i, int e, const Eigen::Vector2d& x) const {
    return flank_turn_point(offset(i, x) - committed_offset_[i], layer_[i], levels_.friction_lr_N_mm3[e],
                            levels_.turn_N_mm4[e], levels_.slide_mm_s[e] * std::max(dt_s_, 0.0));
  }
  double offset(std::size_t i, const Eigen::Vector2d& x) const { return tangent_[i].dot(x - cord_[i]); }
  Eigen::Vector2d normal(std::size_t i) const { return {-tangent_[i].y(), tangent_[i].x()}; }  // (sin φ, cos φ)

  int points_ = 0;  // per element
  bool stick_ = false, slide_ = false, turn_ = false, history_ = false;  // history: either; frames at every λ, offsets committed
  std::vector<double> path_x_, reference_depth_, slip_;
  std::vector<double> committed_offset_, next_offset_;  // along the cord from the column's cord point
  std::vector<double> next_slip_;
  std::vector<double> layer_, next_layer_;  // the turn's layer force d per point (flank_turn_point)
  double committed_time_s_ = 0.0, next_time_s_ = 0.0, dt_s_ = 0.0;
  bool pending_ = false;  // committed into next_*, taken at the next prepare
  std::function<NeutralCurve(double)> curve_at_;
  std::function<void(double, FlankLevels&)> levels_at_;
  std::optional<NeutralCurve> curve_;
  CurveStarts starts_;
  FlankLevels levels_;
  std::vector<double> s_hint_;
  std::vector<Eigen::Vector2d> cord_, tangent_;
};

FlankContact::FlankContact(const Mesh& m, const std::vector<double>& path_x_mm, Integration integration,
                           const NeutralCurve& reference_curve, std::function<NeutralCurve(double)> curve_at,
                           bool stick, bool slide, bool turn, std::function<void(double, FlankLevels&)> levels)
    : stick_(stick), slide_(slide), turn_(turn), history_(stick || slide || turn), curve_at_(std::move(curve_at)),
      levels_at_(std::move(levels)) {
  const auto rule = detail::gauss_rule(gauss_order(m, integration));
  const int npe = m.nodes_per_element;
  points_ = static_cast<int>(rule.size());
  double N[8], dxi[8], deta[8];
  std::vector<Eigen::Vector2d> reference;  // each point's reference position
  for (int e = 0; e < m.element_count(); ++e)
    for (const auto& g : rule) {
      detail::shape(npe, g.xi, g.eta, N, dxi, deta);
      Eigen::Vector2d X = Eigen::Vector2d::Zero();
      double x = 0.0;
      for (int a = 0; a < npe; ++a) X += N[a] * m.X[m.elements[e][a]], x += N[a] * path_x_mm[m.elements[e][a]];
      path_x_.push_back(x);
      reference_depth_.push_back(reference_curve.coordinates(X.x(), X.y()).h_mm);
      reference.push_back(X);
    }
  const std::size_t elements = static_cast<std::size_t>(m.element_count());
  for (auto* v : {&levels_.radial_N_mm4, &levels_.stick_N_mm4, &levels_.stick_limit_N_mm3, &levels_.slide_mm_s,
                  &levels_.turn_N_mm4})
    v->assign(elements, 0.0);
  levels_.friction_lr_N_mm3.assign(elements, Eigen::Vector2d::Zero());
  s_hint_.assign(path_x_.size(), 0.0);
  if (history_) start_offsets(reference);
}

void FlankContact::start_offsets(const std::vector<Eigen::Vector2d>& reference) {
  const std::size_t n = path_x_.size();
  cord_.assign(n, Eigen::Vector2d::Zero()), tangent_.assign(n, Eigen::Vector2d::Zero());
  const NeutralCurve start = curve_at_(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const CurvePoint c = start.at(start.s_from_unstrained(path_x_[i]));
    const Eigen::Vector2d t(std::cos(c.phi_rad), -std::sin(c.phi_rad));
    committed_offset_.push_back(t.dot(reference[i] - Eigen::Vector2d(c.x_mm, c.y_mm)));
    slip_.push_back(committed_offset_.back());
  }
  next_offset_ = committed_offset_, next_slip_ = slip_;
  layer_.assign(n, 0.0), next_layer_ = layer_;
}

void FlankContact::prepare(double lambda) {
  if (pending_) {  // the commit takes effect at the next level (a snapshot at the committed one sees the step's force)
    committed_offset_.swap(next_offset_), slip_.swap(next_slip_), layer_.swap(next_layer_);
    committed_time_s_ = next_time_s_, pending_ = false;
  }
  levels_at_(lambda, levels_);
  dt_s_ = levels_.time_s - committed_time_s_;
  const auto& k = levels_.radial_N_mm4;
  const bool any_radial = std::any_of(k.begin(), k.end(), [](double v) { return v > 0.0; });
  if (!any_radial && !history_) return;
  curve_.emplace(curve_at_(lambda));
  if (any_radial) starts_ = curve_->starts();
  place_feet();
}

void FlankContact::place_feet() {
  for (std::size_t e = 0; e < levels_.radial_N_mm4.size(); ++e)
    for (int g = 0; g < points_; ++g) {
      const std::size_t i = e * points_ + g;
      if (!radial(static_cast<int>(e)) && !history_) continue;
      const double s = curve_->s_from_unstrained(path_x_[i]);
      if (radial(static_cast<int>(e))) s_hint_[i] = s;
      if (!history_) continue;
      const CurvePoint c = curve_->at(s);  // the column's cord point: the foot the stick holds to
      cord_[i] = {c.x_mm, c.y_mm}, tangent_[i] = {std::cos(c.phi_rad), -std::sin(c.phi_rad)};
    }
}

bool FlankContact::at_point(int e, int g, const Eigen::Vector2d& x, Eigen::Vector2d& b, Eigen::Matrix2d& db) const {
  const bool on_radial = radial(e), on_stick = stick_ && sticks(e), on_slide = slide_ && slides(e);
  const bool on_turn = turn_ && turns(e);
  if (!on_radial && !on_stick && !on_slide && !on_turn) return false;
  const std::size_t i = static_cast<std::size_t>(e) * points_ + g;
  if (on_radial) {
    const FlankFoundationPoint p = flank_foundation_point(curve_->coordinates(x.x(), x.y(), starts_, s_hint_[i]),
                                                          reference_depth_[i], levels_.radial_N_mm4[e]);
    b = p.b_N_mm3, db = p.db_dx_N_mm4;
  } else {
    b.setZero(), db.setZero();
  }
  if (on_stick) {  // B_t t with ∂w/∂x = t (the frame is fixed at λ)
    const FlankStickPoint p = flank_stick_point(offset(i, x), slip_[i], levels_.stick_N_mm4[e], levels_.stick_limit_N_mm3[e]);
    b += p.B_t_N_mm3 * tangent_[i];
    db += p.dB_dw_N_mm4 * tangent_[i] * tangent_[i].transpose();
  }
  if (on_slide) {  // u̇ = ((w − w_n) / Δt, 0): only the motion along the belt is beyond Report I's sliding
    Eigen::Matrix2d Q;
    Q.col(0) = tangent_[i], Q.col(1) = normal(i);
    const FlankSlidePoint p = flank_slide_point(Eigen::Vector2d((offset(i, x) - committed_offset_[i]) / dt_s_, 0.0),
                                                levels_.friction_lr_N_mm3[e], levels_.slide_mm_s[e],
                                                levels_.slide_floor_mm_s);
    b += Q * p.b_lr_N_mm3;
    db += Q * p.db_dv_lr.col(0) * tangent_[i].transpose() / dt_s_;  // ∂u̇/∂x = (tᵀ/Δt, 0): unsymmetric
  }
  if (on_turn) {  // ∂w/∂x = tᵀ
    Eigen::Matrix2d Q;
    Q.col(0) = tangent_[i], Q.col(1) = normal(i);
    const FlankTurnPoint p = turn_at(i, e, x);
    b += Q * p.b_lr_N_mm3;
    db += Q * p.db_dw_lr_N_mm4 * tangent_[i].transpose();
  }
  return true;
}

void FlankContact::commit(const ConvergedLoads& state) {
  if (!history_) return;
  const std::vector<Eigen::Vector2d>& x = *state.point_x_mm;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const int e = static_cast<int>(i / points_);
    next_offset_[i] = offset(i, x[i]);
    next_time_s_ = levels_.time_s;
    next_slip_[i] = flank_stick_point(offset(i, x[i]), slip_[i], stick_ && sticks(e) ? levels_.stick_N_mm4[e] : 0.0,
                                      levels_.stick_limit_N_mm3[e])
                        .slip_after_mm;
    next_layer_[i] = turn_ && turns(e) ? turn_at(i, e, x[i]).layer_after_N_mm3 : 0.0;
    pending_ = true;
  }
}

}  // namespace

LoadPtr flank_contact(const Mesh& m, const std::vector<double>& path_x_mm, Integration integration,
                      const NeutralCurve& reference_curve, std::function<NeutralCurve(double)> curve_at, bool stick,
                      bool slide, bool turn, std::function<void(double, FlankLevels&)> levels) {
  return std::make_shared<FlankContact>(m, path_x_mm, integration, reference_curve, std::move(curve_at), stick, slide,
                                        turn, std::move(levels));
}

LoadPtr flank_foundation(const Mesh& m, const std::vector<double>& path_x_mm, Integration integration,
                         const NeutralCurve& reference_curve, std::function<NeutralCurve(double)> curve_at,
                         std::function<void(double, std::vector<double>&)> stiffness) {
  return flank_contact(m, path_x_mm, integration, reference_curve, std::move(curve_at), false, false, false,
                       [stiffness = std::move(stiffness)](double lambda, FlankLevels& levels) {
                         stiffness(lambda, levels.radial_N_mm4);
                       });
}

}  // namespace fitlib::segment
