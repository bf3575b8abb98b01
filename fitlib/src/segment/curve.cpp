#include "fitlib/segment/curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fitlib/core/error.hpp"

namespace fitlib::segment {
namespace {

// sin(x)/x without the cancellation at x → 0.
double sinc(double x) { return std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }

// Below this |K| an interval is a straight line (5.15); the arc error K·Δs²/2 is far below round-off.
constexpr double kStraight = 1e-12;

}  // namespace

NeutralCurve NeutralCurve::uniform(double curvature_1_mm, double strain, double half_length_mm, int n) {
  const std::vector<double> K(n, curvature_1_mm), eps(n + 1, strain);
  return NeutralCurve(half_length_mm / n, K, eps, K, eps);
}

NeutralCurve::NeutralCurve(double ds_mm, std::vector<double> curvature_pos, std::vector<double> strain_pos,
                           std::vector<double> curvature_neg, std::vector<double> strain_neg)
    : ds_(ds_mm), k_pos_(std::move(curvature_pos)), eps_pos_(std::move(strain_pos)),
      k_neg_(std::move(curvature_neg)), eps_neg_(std::move(strain_neg)) {
  if (!(ds_ > 0.0) || k_pos_.empty() || k_pos_.size() != k_neg_.size() ||
      eps_pos_.size() != k_pos_.size() + 1 || eps_neg_.size() != k_neg_.size() + 1)
    throw core::UsageError("NeutralCurve: n curvatures and n + 1 strains per side, Δs > 0");
  for (const auto* v : {&eps_pos_, &eps_neg_})
    for (double e : *v)
      if (!(e > -1.0)) throw core::UsageError("NeutralCurve: strain must exceed −1");
}

// Walks one side from the origin; the negative side is the mirror image of a positive walk.
CurvePoint NeutralCurve::walk(double s_abs, bool positive) const {
  const auto& K = positive ? k_pos_ : k_neg_;
  const auto& eps = positive ? eps_pos_ : eps_neg_;
  CurvePoint p;
  p.K_1_mm = K.empty() ? 0.0 : K[0];
  p.strain = eps.empty() ? 0.0 : eps[0];
  double left = s_abs;
  for (std::size_t i = 0; i < K.size() && left > 0.0; ++i) {
    const double d = (i + 1 == K.size()) ? left : std::min(left, ds_);
    const double a0 = 1.0 / (1.0 + eps[i]);
    const double a1 = (i + 1 == K.size() && d > ds_) ? a0 : 1.0 / (1.0 + eps[i + 1]);  // as unstrained_from_s
    const double frac = std::min(1.0, d / ds_);
    p.K_1_mm = K[i];
    p.strain = 1.0 / (a0 + (a1 - a0) * frac) - 1.0;
    const double half = 0.5 * K[i] * d;
    const double mid = p.phi_rad + half;
    p.x_mm += d * std::cos(mid) * sinc(half);   // (sin φ_end − sin φ)/K, 5.11 rearranged
    p.y_mm -= d * std::sin(mid) * sinc(half);   // (cos φ_end − cos φ)/K, 5.12 rearranged
    p.phi_rad += K[i] * d;
    left -= d;
  }
  if (!positive) {
    p.x_mm = -p.x_mm;
    p.phi_rad = -p.phi_rad;
  }
  return p;
}

CurvePoint NeutralCurve::at(double s_mm) const { return walk(std::abs(s_mm), s_mm >= 0.0); }

// ds_org/ds = 1/(1 + ε) linear in s within an interval (5.17–5.20).
double NeutralCurve::unstrained_from_s(double s_mm) const {
  const auto& eps = s_mm >= 0.0 ? eps_pos_ : eps_neg_;
  const std::size_t n = eps.size() - 1;
  double left = std::abs(s_mm), s_org = 0.0;
  for (std::size_t i = 0; i < n && left > 0.0; ++i) {
    const double a0 = 1.0 / (1.0 + eps[i]);
    const double a1 = (i + 1 == n && left > ds_) ? a0 : 1.0 / (1.0 + eps[i + 1]);
    const double d = (i + 1 == n) ? left : std::min(left, ds_);
    s_org += a0 * d + (a1 - a0) * d * d / (2.0 * ds_);
    left -= d;
  }
  return s_mm >= 0.0 ? s_org : -s_org;
}

// Corrected 5.19: δs_i = 2(1+ε_i) δs_org / {1 + √[1 − 2(ε_{i+1}−ε_i)(1+ε_i) δs_org / (Δs(1+ε_{i+1}))]}.
double NeutralCurve::s_from_unstrained(double s_org_mm) const {
  const auto& eps = s_org_mm >= 0.0 ? eps_pos_ : eps_neg_;
  const std::size_t n = eps.size() - 1;
  double left = std::abs(s_org_mm), s = 0.0;
  for (std::size_t i = 0; i < n && left > 0.0; ++i) {
    const double e0 = eps[i], e1 = eps[i + 1];
    const double whole_org = ds_ * 0.5 * (1.0 / (1.0 + e0) + 1.0 / (1.0 + e1));
    if (i + 1 < n && left >= whole_org) {
      s += ds_;
      left -= whole_org;
      continue;
    }
    const double root = 1.0 - 2.0 * (e1 - e0) * (1.0 + e0) * left / (ds_ * (1.0 + e1));
    if (i + 1 == n && (left > whole_org || root < 0.0)) {  // beyond the last interval: ε constant
      s += ds_ + (left - whole_org) * (1.0 + e1);
    } else {
      s += 2.0 * (1.0 + e0) * left / (1.0 + std::sqrt(root));
    }
    left = 0.0;
  }
  return s_org_mm >= 0.0 ? s : -s;
}

// Inverse map 5.10–5.15: the interval whose arc (or line) has the point's foot inside it, closest.
CurveCoordinates NeutralCurve::coordinates(double x_mm, double y_mm) const {
  CurveCoordinates best;
  double best_h = std::numeric_limits<double>::infinity();
  for (bool positive : {true, false})
    for (std::size_t i = 0; i < k_pos_.size(); ++i) foot(i, positive, walk(ds_ * static_cast<double>(i), positive), x_mm, y_mm, best, best_h);
  return best;
}

CurveStarts NeutralCurve::starts() const {
  CurveStarts out;
  for (std::size_t i = 0; i < k_pos_.size(); ++i) {
    out.positive.push_back(walk(ds_ * static_cast<double>(i), true));
    out.negative.push_back(walk(ds_ * static_cast<double>(i), false));
  }
  return out;
}

CurveCoordinates NeutralCurve::coordinates(double x_mm, double y_mm, const CurveStarts& starts, double s_hint_mm) const {
  CurveCoordinates best;
  double best_h = std::numeric_limits<double>::infinity();
  const std::size_t n = k_pos_.size();
  const bool positive = s_hint_mm >= 0.0;
  const std::size_t at = std::min(n - 1, static_cast<std::size_t>(std::abs(s_hint_mm) / ds_));
  const auto& side = positive ? starts.positive : starts.negative;
  foot(at, positive, side[at], x_mm, y_mm, best, best_h);
  const double none = std::numeric_limits<double>::infinity();
  for (std::size_t i : {at - 1, at + 1})  // the neighbours (at − 1 wraps beyond n when at = 0)
    if (best_h == none && i < n) foot(i, positive, side[i], x_mm, y_mm, best, best_h);
  if (best_h == none && at <= 1) foot(0, !positive, (positive ? starts.negative : starts.positive)[0], x_mm, y_mm, best, best_h);
  for (bool p : {true, false})  // none of those: all intervals, as coordinates(x, y)
    for (std::size_t i = 0; best_h == none && i < n; ++i)
      foot(i, p, (p ? starts.positive : starts.negative)[i], x_mm, y_mm, best, best_h);
  return best;
}

void NeutralCurve::foot(std::size_t i, bool positive, CurvePoint si, double x_mm, double y_mm, CurveCoordinates& best,
                        double& best_h) const {
  const auto& K = positive ? k_pos_ : k_neg_;
  const double px = positive ? x_mm : -x_mm;  // mirror the negative side onto a positive walk
  if (!positive) {  // undo the mirror: work on the positive-side image
    si.x_mm = -si.x_mm;
    si.phi_rad = -si.phi_rad;
  }
  double ds, h, phi;
  if (std::abs(K[i]) < kStraight) {
    const double dx = px - si.x_mm, dy = y_mm - si.y_mm;
    ds = dx * std::cos(si.phi_rad) - dy * std::sin(si.phi_rad);
    h = -dx * std::sin(si.phi_rad) - dy * std::cos(si.phi_rad);
    phi = si.phi_rad;
  } else {
    const double xr = si.x_mm - std::sin(si.phi_rad) / K[i];  // 5.11
    const double yr = si.y_mm - std::cos(si.phi_rad) / K[i];  // 5.12
    const double dx = px - xr, dy = y_mm - yr;
    const double sgn = K[i] > 0.0 ? 1.0 : -1.0;
    phi = std::atan2(sgn * dx, sgn * dy);                      // 5.10
    ds = (phi - si.phi_rad) / K[i];
    h = sgn * (1.0 / std::abs(K[i]) - std::hypot(dx, dy));    // 5.13
  }
  const bool last = i + 1 == K.size();
  const double tol = 1e-9 * ds_;
  if (ds < -tol) return;
  if (ds > ds_ + tol && !last) return;
  if (std::abs(h) < best_h) {
    best_h = std::abs(h);
    const double s = ds_ * static_cast<double>(i) + ds;
    best = {positive ? phi : -phi, positive ? s : -s, h, K[i]};
  }
}

}  // namespace fitlib::segment
