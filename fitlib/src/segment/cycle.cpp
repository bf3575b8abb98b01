// The segment driven by the load cycle (fitlib/segment/cycle.hpp; docs/segment.md).
#include "fitlib/segment/cycle.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "element.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/segment/curve.hpp"
#include "fitlib/segment/end_faces.hpp"
#include "fitlib/segment/flank.hpp"

namespace fitlib::segment {
namespace {

// The straight mesh wrapped on the mould circle (curvature K_m, unstrained cord line): the
// stress-free reference of the moulded belt.
Mesh wrapped(const Mesh& straight, double K_m) {
  Mesh m = straight;
  const NeutralCurve mould = NeutralCurve::uniform(K_m, 0.0, 1.5 * straight.half_length_mm);
  for (Eigen::Vector2d& X : m.X) {
    const CurvePoint q = mould.at(X.x());
    X = Eigen::Vector2d(q.x_mm, q.y_mm) + X.y() * Eigen::Vector2d(std::sin(q.phi_rad), std::cos(q.phi_rad));
  }
  return m;
}

// ∫ K ds of the history's curvature from its first sample to s (any real s, periodic), exact for
// the piecewise-linear interpolation with its jumps (belt::LoadHistory).
class CurvatureIntegral {
 public:
  explicit CurvatureIntegral(const belt::LoadHistory& h) : L_(h.length_mm()) {
    const auto& q = h.samples();
    for (std::size_t k = 0; k < q.size(); ++k) {
      const belt::LoadState& b = k + 1 < q.size() ? q[k + 1] : q.front();
      const double end = k + 1 < q.size() ? b.s_mm : b.s_mm + L_;
      pieces_.push_back({q[k].s_mm, end, q[k].K_1_mm, b.K_1_mm, total_});
      total_ += 0.5 * (end - q[k].s_mm) * (q[k].K_1_mm + b.K_1_mm);
    }
  }
  double operator()(double s) const {
    const double t = s - pieces_.front().a, turns = std::floor(t / L_), x = pieces_.front().a + (t - turns * L_);
    auto it = std::upper_bound(pieces_.begin(), pieces_.end(), x, [](double v, const Piece& p) { return v < p.a; });
    const Piece& p = *(it - 1);
    const double w = p.b > p.a ? (x - p.a) / (p.b - p.a) : 0.0;
    return turns * total_ + p.before + 0.5 * (x - p.a) * (2.0 * p.Ka + w * (p.Kb - p.Ka));
  }

 private:
  struct Piece {
    double a, b, Ka, Kb, before;
  };
  double L_, total_ = 0.0;
  std::vector<Piece> pieces_;
};

// Cord curve at pseudo time τ: step 1 (τ ≤ 1) blends the mould curvature into the cycle's start
// state; step 2 reads the history at s0 + ξ, s0 = (τ − 1) L. Each interval's curvature is the
// history's mean over it (not a sample at its middle), so the curve moves continuously in τ when
// a curvature jump (a pulley's entrance) passes through the segment (docs/decisions.md).
NeutralCurve cord_curve(double tau, const belt::LoadHistory& h, const CurvatureIntegral& integral, double K_m,
                        double reach_mm, int n) {
  const double w = std::min(1.0, tau), s0 = std::max(0.0, tau - 1.0) * h.length_mm();
  const double ds = reach_mm / n;
  std::array<std::vector<double>, 2> K, eps;
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    for (int i = 0; i <= n; ++i) {
      eps[side].push_back(w * h.at_position(s0 + sign * i * ds).strain);
      if (i == n) break;
      const double mean = (integral(s0 + sign * (i + 1) * ds) - integral(s0 + sign * i * ds)) / (sign * ds);
      K[side].push_back((1.0 - w) * K_m + w * mean);
    }
  }
  return NeutralCurve(ds, K[0], eps[0], K[1], eps[1]);
}

double reference_area(const Mesh& m, int e, const std::vector<detail::GaussPoint>& rule) {
  double area = 0.0;
  for (const auto& g : rule) area += reference_jacobian(m, e, g.xi, g.eta) * g.weight;
  return area;
}

// A face node's share of a traction t(h) on the end face: Σ over its edges ∫ N_a t dl by 3-point
// Gauss, written as t at the Gauss points' depths times weights (one entry per node and point).
struct FaceWeight {
  int node;
  double depth_mm, length_mm;
};

std::vector<FaceWeight> face_weights(const Mesh& straight, const std::vector<int>& face) {
  std::vector<FaceWeight> out;
  const int step = straight.nodes_per_element == 8 ? 2 : 1;
  const double xi[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, wt[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  for (std::size_t a = 0; a + step < face.size(); a += step) {
    const double ya = straight.X[face[a]].y(), yb = straight.X[face[a + step]].y(), half = 0.5 * std::abs(ya - yb);
    for (int g = 0; g < 3; ++g) {
      const double x = xi[g], depth = -(0.5 * (ya + yb) + 0.5 * x * (yb - ya));
      const double N2[3] = {0.5 * x * (x - 1.0), 1.0 - x * x, 0.5 * x * (x + 1.0)}, N1[2] = {0.5 * (1.0 - x), 0.5 * (1.0 + x)};
      for (int k = 0; k <= step; ++k)
        out.push_back({face[a + k], depth, (step == 2 ? N2[k] : N1[k]) * wt[g] * half});
    }
  }
  return out;
}

CycleSample local_sample(const IntegrationPointStress& ip, double phi) {
  const Eigen::Vector2d t(std::cos(phi), -std::sin(phi)), n(std::sin(phi), std::cos(phi));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(ip.F * ip.F.transpose());
  const Eigen::Matrix2d e = eig.eigenvectors() * (0.5 * eig.eigenvalues().array().log()).matrix().asDiagonal() *
                            eig.eigenvectors().transpose();
  CycleSample c;
  c.s11_MPa = n.dot(ip.cauchy_MPa * n), c.s22_MPa = t.dot(ip.cauchy_MPa * t), c.s12_MPa = n.dot(ip.cauchy_MPa * t);
  c.s33_MPa = ip.sigma33_MPa;
  c.e11 = n.dot(e * n), c.e22 = t.dot(e * t), c.e12 = n.dot(e * t);
  return c;
}

// The increment's forces along the cord tangent at the middle: the cord line's reactions, the left
// end face's (without the cord node) and the rubber's section force through x = 0.
void longitudinal_loads(const StaticProblem& p, const StaticSolution& s, const NeutralCurve& curve, const Mesh& m,
                        const std::vector<double>& path_x, Integration integration, IncrementLoads& q) {
  const double phi = curve.at(curve.s_from_unstrained(0.0)).phi_rad;
  const Eigen::Vector2d t(std::cos(phi), -std::sin(phi));
  q.cord_longitudinal_N_mm = q.cord_reaction_N_mm.dot(t);
  for (int node : m.left_nodes)
    if (node != m.top_nodes.front()) q.left_end_longitudinal_N_mm += s.reaction_N_mm[node].dot(t);
  for (int node : m.top_nodes)
    if (m.X[node].x() < 0.0) q.left_cord_longitudinal_N_mm += s.reaction_N_mm[node].dot(t);
  for (std::size_t node = 0; node < s.inertia_N_mm.size(); ++node)  // SolverKnobs::inertia
    if (path_x[node] < 0.0) q.left_inertia_longitudinal_N_mm += s.inertia_N_mm[node].dot(t);
  q.rubber_section_N_mm = section_force(p, s, 0.0, Eigen::Vector2d::Zero(), integration).force_N_mm.dot(t);
}

}  // namespace

void flank_shares(CycleResult& run) {
  double largest = 0.0, sum = 0.0;
  int count = 0;
  for (const IncrementLoads& q : run.loads) largest = std::max(largest, q.contact_radial_N_mm);
  run.flank_radial_share = run.flank_radial_mean_share = 0.0;
  for (const IncrementLoads& q : run.loads)
    if (largest > 0.0 && q.contact_radial_N_mm >= 0.5 * largest) {
      const double share = q.flank_radial_N_mm / q.contact_radial_N_mm;
      if (std::abs(share) > std::abs(run.flank_radial_share)) run.flank_radial_share = share;
      sum += share, ++count;
    }
  if (count) run.flank_radial_mean_share = sum / count;
  double dead = 0.0, stick = 0.0;  // the stick's longitudinal total against the dead friction's
  for (const IncrementLoads& q : run.loads)
    dead = std::max(dead, std::abs(q.contact_longitudinal_N_mm)), stick = std::max(stick, std::abs(q.flank_longitudinal_N_mm));
  run.flank_stick_share = dead > 0.0 ? stick / dead : 0.0;  // 0 without a law along the belt
}

double span_cord_share_bound(const CycleResult& run) {
  using B = EquilibriumBounds;
  if (run.history) return B::span_cord_share_with_history;
  return run.sheared_ends ? B::span_cord_share_sheared_ends : B::span_cord_share;
}

Eigen::Vector2d contact_body_force(const belt::LoadState& q, const CycleDrive& d) {
  if (!(q.p_MPa > 0.0)) return Eigen::Vector2d::Zero();
  const double cb = std::cos(d.wedge_half_angle_rad), sb = std::sin(d.wedge_half_angle_rad);
  const double area_factor = q.p_MPa * 2.0 / d.width_mm / cb;  // cos β_s = 1 (docs/decisions.md)
  const double inertia = d.density_kg_m3 * 1e-12 * q.K_1_mm * d.speed_mm_s * d.speed_mm_s;  // ρKV², N/mm³
  // μ is the load cycle's friction used: the drive's μ, ramped to zero and back at the driver's
  // exit (belt-mechanics.md §2.5), as the beam level reads it.
  const double B_l = -q.friction_used * area_factor * std::sin(q.gamma_rad);                  // (6.6)
  const double B_r = area_factor * (sb - q.friction_used * std::cos(q.gamma_rad)) + inertia;   // (6.7)
  return {B_l, B_r};
}

namespace {

// Periodic moving average of v over ±half_width cells (the total is kept).
std::vector<double> windowed(const std::vector<double>& v, int half_width) {
  const int M = static_cast<int>(v.size());
  if (half_width <= 0) return v;
  std::vector<double> prefix(3 * M + 1, 0.0), out(M);  // v three times over: the window never leaves it
  for (int i = 0; i < 3 * M; ++i) prefix[i + 1] = prefix[i] + v[i % M];
  const int w = std::min(half_width, M / 2 - 1);
  for (int i = 0; i < M; ++i) {
    const int lo = i - w + M;  // cells i − w … i + w, shifted by one period
    out[i] = (prefix[lo + 2 * w + 1] - prefix[lo]) / (2 * w + 1);
  }
  return out;
}

}  // namespace

std::vector<double> cycle_breakpoints(const belt::LoadHistory& h, int steps, double weight, double reach_mm) {
  if (steps < 1) throw core::UsageError("segment cycle: steps_per_cycle must be ≥ 1");
  const int M = 4000;
  const double L = h.length_mm(), ds = L / M;
  std::vector<double> dK(M), dp(M);
  double tvK = 0.0, tvp = 0.0;
  for (int i = 0; i < M; ++i) {
    const belt::LoadState a = h.at_position(i * ds), b = h.at_position((i + 1) * ds);
    dK[i] = std::abs(b.K_1_mm - a.K_1_mm), dp[i] = std::abs(b.p_MPa - a.p_MPa);
    tvK += dK[i], tvp += dp[i];
  }
  // The segment feels a change while any of it is over it: spread each change over ±reach.
  const int half_width = static_cast<int>(std::lround(reach_mm / ds));
  dK = windowed(dK, half_width), dp = windowed(dp, half_width);
  std::vector<double> cumulative(M + 1, 0.0);
  for (int i = 0; i < M; ++i)
    cumulative[i + 1] = cumulative[i] + 1.0 / M + weight * 0.5 * ((tvK > 0 ? dK[i] / tvK : 0.0) + (tvp > 0 ? dp[i] / tvp : 0.0));
  // The cycle's end is not searched: back() · steps / steps can round above back(), where lower_bound
  // returns end() (a read past the table, found by the sanitizer build); the clamp guards the rest.
  std::vector<double> tau;
  for (int k = 1; k < steps; ++k) {
    const double target = cumulative.back() * k / steps;
    const int i = std::min(M, static_cast<int>(std::lower_bound(cumulative.begin(), cumulative.end(), target) -
                                               cumulative.begin()));
    const double s = i == 0 ? 0.0 : (i - 1 + (target - cumulative[i - 1]) / (cumulative[i] - cumulative[i - 1])) / M;
    if (tau.empty() || s > tau.back() + 1e-9) tau.push_back(s);
  }
  if (tau.empty() || 1.0 > tau.back() + 1e-9) tau.push_back(1.0);  // the cycle's end
  return tau;
}

namespace {

// Where the last converged increment was, in the user's terms: the bending step, or the cycle and
// the path position with the load there (the message's prefix).
std::string where_in_cycle(double tau, const belt::LoadHistory& h) {
  std::ostringstream m;
  m << "segment load cycle: ";
  if (tau < 1.0) {
    m << "failed in the bending step (" << core::format_number(100.0 * tau, 3) << " % of it); ";
    return m.str();
  }
  const int cycle = static_cast<int>(std::floor(tau - 1.0)) + 1;
  const double s = (tau - cycle) * h.length_mm();
  const belt::LoadState at = h.at_position(s);
  m << "failed in cycle " << cycle << " after path position " << core::format_number(s, 4) << " mm of "
    << core::format_number(h.length_mm(), 4) << " mm from the slack span's middle (curvature "
    << core::format_number(at.K_1_mm, 4) << " 1/mm, side pressure " << core::format_number(at.p_MPa, 4)
    << " MPa there); ";
  return m.str();
}

}  // namespace

namespace {

// The sheared end condition: each face warped and sheared as a long belt's section under the
// friction and the changes of strain and curvature at the face's path position, each smoothed by
// the shear lag (segment/end_faces.hpp); tabulated once over the cycle.
void long_belt_ends(const CogSection& section, const Mesh& straight, const std::array<const PlaneStrainLaw*, 2>& laws,
                    const CycleDrive& drive, CycleKnobs::EndProfile& warping, CycleKnobs::EndProfile& shear) {
  const double half = straight.half_length_mm;
  const std::array<LongBeltSection, 2> faces{LongBeltSection(section, -half, laws), LongBeltSection(section, half, laws)};
  const belt::LoadHistory& h = *drive.history;
  const int M = 4000;
  const double L = h.length_mm(), ds = L / M;
  std::array<std::vector<double>, 3> load;  // b, ε, K along the cycle
  for (auto& v : load) v.resize(M);
  for (int i = 0; i < M; ++i) {
    const belt::LoadState q = h.at_position(i * ds);
    load[0][i] = contact_body_force(q, drive).x(), load[1][i] = q.strain, load[2][i] = q.K_1_mm;
  }
  for (auto& v : load) v = shear_lag_smoothed(v, ds, faces[0].shear_lag_mm());
  std::vector<SectionGradients> g(M);
  for (int i = 0; i < M; ++i) {
    const int next = (i + 1) % M, prev = (i + M - 1) % M;
    g[i] = {load[0][i], (load[1][next] - load[1][prev]) / (2.0 * ds), (load[2][next] - load[2][prev]) / (2.0 * ds)};
  }
  auto at = [g, ds, L, M, half](int side, double s_mm) {  // linear between the samples, periodic
    const double u = std::fmod(std::fmod(s_mm + (side == 0 ? -half : half), L) + L, L) / ds, i = std::floor(u), w = u - i;
    const int k = static_cast<int>(i) % M, k1 = (k + 1) % M;
    return SectionGradients{g[k].body_N_mm3 + w * (g[k1].body_N_mm3 - g[k].body_N_mm3),
                            g[k].strain_per_mm + w * (g[k1].strain_per_mm - g[k].strain_per_mm),
                            g[k].curvature_per_mm2 + w * (g[k1].curvature_per_mm2 - g[k].curvature_per_mm2)};
  };
  warping = [faces, at](int side, double depth_mm, double s_mm) { return faces[side].warping_mm(at(side, s_mm), depth_mm); };
  shear = [faces, at](int side, double depth_mm, double s_mm) { return faces[side].shear_MPa(at(side, s_mm), depth_mm); };
}

// The sheared faces' warping as the constraints' shift along the cord tangent (none in step 1).
EndShift end_shift(const Mesh& straight, const belt::LoadHistory& h, double T, const CycleKnobs::EndProfile& warping) {
  if (!warping) return {};
  return [&straight, &h, T, warping](int node, double lambda) {
    const double tau = lambda * T;
    if (tau <= 1.0) return 0.0;
    const Eigen::Vector2d& X = straight.X[node];
    return warping(X.x() < 0.0 ? 0 : 1, -X.y(), (tau - 1.0) * h.length_mm());
  };
}

// The faces' shear traction as dead nodal forces along each end's radial line (none in step 1).
std::function<void(double, std::vector<Eigen::Vector2d>&)> end_shear_forces(
    int nodes, const Mesh& straight, const std::vector<double>& path_x, const belt::LoadHistory& h, double T,
    std::function<NeutralCurve(double)> curve_at, CycleKnobs::EndProfile shear) {
  const std::array<std::vector<FaceWeight>, 2> faces{face_weights(straight, straight.left_nodes),
                                                     face_weights(straight, straight.right_nodes)};
  const std::array<double, 2> end_x{path_x[straight.top_nodes.front()], path_x[straight.top_nodes.back()]};
  return [=, &h](double lambda, std::vector<Eigen::Vector2d>& f) {
    f.assign(nodes, Eigen::Vector2d::Zero());
    const double tau = lambda * T;
    if (tau <= 1.0) return;
    const NeutralCurve curve = curve_at(lambda);
    const double s0 = (tau - 1.0) * h.length_mm();
    for (int side = 0; side < 2; ++side) {
      const double phi = curve.at(curve.s_from_unstrained(end_x[side])).phi_rad;
      const Eigen::Vector2d n(std::sin(phi), std::cos(phi));  // radial, outward
      const double outward = side == 0 ? -1.0 : 1.0;          // the face's normal is ∓ the tangent
      for (const FaceWeight& w : faces[side]) f[w.node] += outward * w.length_mm * shear(side, w.depth_mm, s0) * n;
    }
  };
}

// The mean of load(state) over element e's path extent with the segment's middle at s0: sampled
// every `sampling_mm` (CycleKnobs::body_force_sampling_mm, the midpoint rule), or at the element's
// centre (0).
struct ElementSampling {
  std::vector<double> centre_x;
  std::vector<std::pair<double, double>> extent_x;
  double sampling_mm = 0.0;

  template <typename T, typename Load>
  T mean(const belt::LoadHistory& h, int e, double s0, const T& zero, Load load) const {
    const double width = extent_x[e].second - extent_x[e].first;
    const int n = sampling_mm > 0.0 ? std::max(1, static_cast<int>(std::ceil(width / sampling_mm))) : 1;
    if (n == 1) return load(h.at_position(s0 + centre_x[e]));
    T sum = zero;
    for (int i = 0; i < n; ++i) sum += load(h.at_position(s0 + extent_x[e].first + (i + 0.5) * width / n));
    return T(sum / n);
  }
};

// The contact body forces per element at load level λ (global, 6.6–6.9): their mean over the
// element's path extent (ElementSampling), turned by the cord's tangent at its centre.
std::function<void(double, std::vector<Eigen::Vector2d>&)> contact_body_forces(ElementSampling sampling,
                                                                               const CycleDrive& drive, double T,
                                                                               std::function<NeutralCurve(double)> curve_at) {
  const belt::LoadHistory& h = *drive.history;
  return [=, &h](double lambda, std::vector<Eigen::Vector2d>& b) {
    const double tau = lambda * T;
    b.assign(sampling.centre_x.size(), Eigen::Vector2d::Zero());
    if (tau > 1.0) {
      const NeutralCurve curve = curve_at(lambda);
      const double s0 = (tau - 1.0) * h.length_mm();
      for (std::size_t e = 0; e < sampling.centre_x.size(); ++e) {
        const Eigen::Vector2d lr = sampling.mean(h, static_cast<int>(e), s0, Eigen::Vector2d(Eigen::Vector2d::Zero()),
                                                 [&](const belt::LoadState& q) { return contact_body_force(q, drive); });
        if (lr.isZero(0.0)) continue;
        const double phi = curve.at(curve.s_from_unstrained(sampling.centre_x[e])).phi_rad;
        b[e] = {std::cos(phi) * lr.x() + std::sin(phi) * lr.y(), -std::sin(phi) * lr.x() + std::cos(phi) * lr.y()};  // 6.8–6.9
      }
    }
  };
}

// The flank's levels per element at λ (segment/flank.hpp): the radial k and the stick's k_t times
// the share of the element's path extent in a sheave (p > 0), so they engage continuously as a
// pulley's entrance passes, and the stick's limit, the unused friction (μ − μ_used) p 2/(B cos β)
// averaged over the extent (the area factor of 6.6).
// The sliding friction's direction: Report I's friction (l, r) averaged over the extent and the
// sliding speed, at least the floor V_0.
std::function<void(double, FlankLevels&)> flank_levels(ElementSampling sampling, const CycleDrive& drive,
                                                       const CycleKnobs& knobs, double T, std::function<double(double)> time_s) {
  const belt::LoadHistory& h = *drive.history;
  const double k = knobs.flank_stiffness_N_mm4, k_t = knobs.flank_stick_N_mm4, mu = drive.friction;
  const double V0 = knobs.flank_slide_floor_mm_s;
  const double area_factor = 2.0 / drive.width_mm / std::cos(drive.wedge_half_angle_rad);
  return [=, &h](double lambda, FlankLevels& levels) {
    const double tau = lambda * T;
    const std::size_t n = sampling.centre_x.size();
    for (auto* v : {&levels.radial_N_mm4, &levels.stick_N_mm4, &levels.stick_limit_N_mm3, &levels.slide_mm_s}) v->assign(n, 0.0);
    levels.friction_lr_N_mm3.assign(n, Eigen::Vector2d::Zero());
    levels.time_s = time_s(lambda), levels.slide_floor_mm_s = V0;
    if (tau <= 1.0) return;
    const double s0 = (tau - 1.0) * h.length_mm();
    for (std::size_t e = 0; e < n; ++e) {
      const int el = static_cast<int>(e);
      const double share = sampling.mean(h, el, s0, 0.0, [](const belt::LoadState& q) { return q.p_MPa > 0.0 ? 1.0 : 0.0; });
      if (k > 0.0) levels.radial_N_mm4[e] = k * share;
      if (V0 > 0.0 && share > 0.0) {
        levels.friction_lr_N_mm3[e] = sampling.mean(h, el, s0, Eigen::Vector2d(Eigen::Vector2d::Zero()), [&](const belt::LoadState& q) {
          const double F = q.p_MPa > 0.0 ? q.friction_used * q.p_MPa * area_factor : 0.0;  // 6.6–6.7's friction
          return Eigen::Vector2d(-F * std::sin(q.gamma_rad), -F * std::cos(q.gamma_rad));
        });
        levels.slide_mm_s[e] = sampling.mean(h, el, s0, 0.0, [&](const belt::LoadState& q) { return std::max(q.slide_mm_s, V0); });
      }
      if (!(k_t > 0.0) || !(share > 0.0)) continue;
      levels.stick_N_mm4[e] = k_t * share;
      levels.stick_limit_N_mm3[e] = sampling.mean(h, el, s0, 0.0, [&](const belt::LoadState& q) {
        return q.p_MPa > 0.0 ? std::max(0.0, mu - q.friction_used) * q.p_MPa * area_factor : 0.0;
      });
    }
  };
}

}  // namespace

CycleResult run_cycle(const CogSection& section, const MeshKnobs& mesh_knobs, const SolverKnobs& solver,
                      const std::array<const PlaneStrainLaw*, 2>& laws, const CycleDrive& drive,
                      const CycleKnobs& knobs, const std::vector<NamedPoint>& extra_points) {
  if (!drive.history) throw core::UsageError("segment cycle: a load history is required");
  if (!(drive.speed_mm_s > 0.0)) throw core::InputError("segment cycle: the belt speed must be > 0 (a belt at rest has no load cycle)");
  if (knobs.cycles < 1) throw core::InputError("segment cycle: cycles must be ≥ 1");
  const belt::LoadHistory& h = *drive.history;
  const Mesh straight = build_mesh(section, mesh_knobs);
  const double K_m = knobs.manufactured_radius_mm > 0.0 ? 1.0 / knobs.manufactured_radius_mm : 0.0;
  const Mesh m = wrapped(straight, K_m);
  std::vector<double> path_x;
  for (const Eigen::Vector2d& X : straight.X) path_x.push_back(X.x());
  const std::vector<double>& at_s = knobs.positions_mm;
  for (std::size_t k = 0; k < at_s.size(); ++k)
    if (!(at_s[k] > (k ? at_s[k - 1] : 0.0)) || !std::isfinite(at_s[k]))
      throw core::UsageError("segment cycle: positions_mm must be positive and increasing");
  const double reach = 1.5 * straight.half_length_mm;
  const double T = 1.0 + (at_s.empty() ? knobs.cycles : at_s.back() / h.length_mm());
  const int n = knobs.curve_intervals;
  const CurvatureIntegral integral(h);
  auto curve_at = [&h, &integral, K_m, reach, n, T](double lambda) {
    return cord_curve(lambda * T, h, integral, K_m, reach, n);
  };
  CycleKnobs::EndProfile warping = knobs.end_warping_mm, shear = knobs.end_shear_MPa;
  if (knobs.ends == EndCondition::sheared && !warping && !shear)
    long_belt_ends(section, straight, laws, drive, warping, shear);
  const EndCondition ends = knobs.ends == EndCondition::free ? EndCondition::free : EndCondition::radial;
  StaticProblem p = cord_curve_problem(m, path_x, laws, curve_at, ends, end_shift(straight, h, T, warping));
  const double period = h.period_s() > 0.0 ? h.period_s() : h.length_mm() / drive.speed_mm_s;
  p.time_s = [T, period](double lambda) { return lambda * T * period; };
  p.temperature_C = drive.temperature_C;
  p.density_t_mm3 = drive.density_kg_m3 * 1e-12;  // the rubber's mass when SolverKnobs::inertia is on

  const int order = gauss_order(m, solver.integration);
  const auto rule = detail::gauss_rule(order);
  std::vector<double> area(m.element_count());
  ElementSampling sampling{std::vector<double>(m.element_count()), std::vector<std::pair<double, double>>(m.element_count()),
                           knobs.body_force_sampling_mm};
  std::vector<double>& centre_x = sampling.centre_x;
  for (int e = 0; e < m.element_count(); ++e) {
    area[e] = reference_area(m, e, rule);
    auto& extent = sampling.extent_x[e];  // the element's path extent
    extent = {path_x[m.elements[e][0]], path_x[m.elements[e][0]]};
    for (int a = 0; a < 4; ++a) {
      const double x = path_x[m.elements[e][a]];
      centre_x[e] += 0.25 * x;
      extent = {std::min(extent.first, x), std::max(extent.second, x)};
    }
  }
  const auto body = contact_body_forces(sampling, drive, T, curve_at);
  p.body_force = body;
  const bool along_belt = knobs.flank_stick_N_mm4 > 0.0 || knobs.flank_slide_floor_mm_s > 0.0;  // a tangential flank law
  if (knobs.flank_stiffness_N_mm4 > 0.0 || along_belt)  // the deformation-limited flank (segment/flank.hpp)
    p.following_force = flank_contact(m, path_x, solver.integration, NeutralCurve::uniform(K_m, 0.0, reach), curve_at,
                                      knobs.flank_stick_N_mm4 > 0.0, knobs.flank_slide_floor_mm_s > 0.0,
                                      flank_levels(sampling, drive, knobs, T, p.time_s));
  if (shear) p.nodal_force = end_shear_forces(m.node_count(), straight, path_x, h, T, curve_at, shear);

  CycleResult out;
  out.cycle_time_s = period;
  std::vector<NamedPoint> named = standard_points(section);
  named.insert(named.end(), extra_points.begin(), extra_points.end());
  std::vector<Eigen::Vector2d> forces, nodal;
  std::vector<bool> written(knobs.vtk_at_s_mm.size(), false);
  auto write_fields = [&](double tau, const StaticSolution& s) {
    if (knobs.vtk_prefix.empty()) return;
    const double s_last = (tau - 1.0 - (knobs.cycles - 1)) * h.length_mm();  // within the last cycle
    for (std::size_t k = 0; k < written.size(); ++k) {
      if (written[k] || s_last < knobs.vtk_at_s_mm[k]) continue;
      VtkFields fields;
      fields.displacement_mm = s.u_mm;
      for (const auto& pts : s.points) {
        std::array<double, 4> mean{};
        for (const IntegrationPointStress& ip : pts) {
          const std::array<double, 4> v{ip.cauchy_MPa(0, 0), ip.cauchy_MPa(1, 1), ip.cauchy_MPa(0, 1), ip.sigma33_MPa};
          for (int c = 0; c < 4; ++c) mean[c] += v[c] / static_cast<double>(pts.size());
        }
        fields.cell_stress_MPa.push_back(mean);
      }
      const std::string path = knobs.vtk_prefix + "-" + std::to_string(k) + ".vtk";
      write_vtk(m, path, fields);
      out.vtk_files.push_back(path);
      written[k] = true;
    }
  };
  double converged_lambda = 0.0;  // the last converged increment, for a failure's message
  p.on_increment = [&](double lambda, const StaticSolution& s) {
    converged_lambda = lambda;
    if (knobs.progress) knobs.progress(lambda);
    if (out.points.empty()) {  // each named point in the moulded reference mesh
      const Mesh one_point = wrapped([&] {
        Mesh q = straight;
        q.X.clear();
        for (const NamedPoint& np : named) q.X.emplace_back(np.x_mm, np.y_mm);
        return q;
      }(), K_m);
      for (std::size_t k = 0; k < named.size(); ++k) {
        MonitoredHistory mh;
        mh.point = named[k];
        mh.X_mm = one_point.X[k];
        mh.at = locate(m, mh.X_mm);
        mh.role = m.roles[mh.at.element];
        out.points.push_back(mh);
      }
    }
    const double tau = lambda * T;
    const NeutralCurve curve = curve_at(lambda);
    for (MonitoredHistory& mh : out.points) {
      CycleSample c = local_sample(interpolate(s, mh.at, order, mh.X_mm),
                                   curve.at(curve.s_from_unstrained(mh.point.x_mm)).phi_rad);
      c.t_s = tau * period;
      c.s_mm = std::max(0.0, tau - 1.0) * h.length_mm();
      mh.samples.push_back(c);
    }
    write_fields(tau, s);
    // Equilibrium: Σ reactions + ∫ b dV = 0 (the free residual is at the tolerance).
    body(lambda, forces);
    Eigen::Vector2d applied = Eigen::Vector2d::Zero(), reactions = Eigen::Vector2d::Zero(), cord = Eigen::Vector2d::Zero();
    double scale = 1e-300;  // Σ |nodal reactions| + Σ |element body forces|
    for (int e = 0; e < m.element_count(); ++e) applied += forces[e] * area[e], scale += (forces[e] * area[e]).norm();
    if (p.nodal_force) {
      p.nodal_force(lambda, nodal);
      for (const Eigen::Vector2d& f : nodal) applied += f, scale += f.norm();
    }
    for (const Eigen::Vector2d& f : s.inertia_N_mm) applied -= f, scale += f.norm();  // d'Alembert (SolverKnobs::inertia)
    for (const Eigen::Vector2d& f : s.following_N_mm) applied += f, scale += f.norm();  // the flank foundation
    for (const Eigen::Vector2d& r : s.reaction_N_mm) reactions += r, scale += r.norm();
    for (int node : m.top_nodes) cord += s.reaction_N_mm[node];
    out.equilibrium_error = std::max(out.equilibrium_error, (reactions + applied).norm() / scale);
    out.max_cord_reaction_N_mm = std::max(out.max_cord_reaction_N_mm, cord.norm());
    IncrementLoads q{tau * period, std::max(0.0, tau - 1.0) * h.length_mm(), cord, applied};
    for (int e = 0; !s.following_N_mm.empty() && e < m.element_count(); ++e) {  // radial: along the outward normal at the element's centre
      const Eigen::Vector2d& flank = s.following_N_mm[e];
      if (forces[e].isZero(0.0) && flank.isZero(0.0)) continue;
      const double phi = curve.at(curve.s_from_unstrained(centre_x[e])).phi_rad;
      const Eigen::Vector2d n(std::sin(phi), std::cos(phi));
      q.contact_radial_N_mm += forces[e].dot(n) * area[e];
      q.flank_radial_N_mm += flank.dot(n);
      if (!along_belt) continue;
      const Eigen::Vector2d t(std::cos(phi), -std::sin(phi));
      q.contact_longitudinal_N_mm += forces[e].dot(t) * area[e];
      q.flank_longitudinal_N_mm += flank.dot(t);
    }
    longitudinal_loads(p, s, curve, m, path_x, solver.integration, q);
    q.belt_force_N_mm = tau > 1.0 ? h.at_position(q.s_mm).F_N / drive.width_mm : 0.0;
    const double K_mid = h.at_position(q.s_mm).K_1_mm;
    q.span = tau > 1.0 && std::all_of(centre_x.begin(), centre_x.end(), [&](double x) {
      const belt::LoadState state = h.at_position(q.s_mm + x);
      return state.p_MPa == 0.0 && std::abs(state.K_1_mm - K_mid) <= 1e-6;
    });
    if (q.span && q.belt_force_N_mm > 0.0) {
      out.span_cord_share = std::max(out.span_cord_share, std::abs(q.cord_longitudinal_N_mm) / q.belt_force_N_mm);
      const double balance = q.left_end_longitudinal_N_mm + q.left_cord_longitudinal_N_mm + q.rubber_section_N_mm -
                           q.left_inertia_longitudinal_N_mm;
      out.span_section_mismatch = std::max(out.span_section_mismatch, std::abs(balance) / std::abs(q.rubber_section_N_mm));
    }
    out.loads.push_back(q);
  };

  const bool history = laws[0]->state_size() > 0 || laws[1]->state_size() > 0;
  SolverKnobs k = solver;
  k.schedule.clear();
  for (int i = 1; i <= knobs.bend_steps; ++i) k.schedule.push_back(static_cast<double>(i) / knobs.bend_steps / T);
  if (!at_s.empty()) {
    for (double s_mm : at_s) k.schedule.push_back(std::min(1.0, (1.0 + s_mm / h.length_mm()) / T));
  } else {
    const std::vector<double> per_cycle = cycle_breakpoints(h, knobs.steps_per_cycle, knobs.change_weight,
                                                                straight.half_length_mm);
    for (int c = 0; c < knobs.cycles; ++c)
      for (double b : per_cycle) {
        const double lambda = std::min(1.0, (1.0 + c + b) / T);
        if (k.schedule.empty() || lambda > k.schedule.back() + 1e-12) k.schedule.push_back(lambda);
      }
  }
  try {
    out.final_state = solve_static(p, k);
  } catch (const core::NumericalError& e) {
    throw core::NumericalError(where_in_cycle(converged_lambda * T, h) + e.what());
  }
  out.increments = out.final_state.increments;
  out.newton_iterations = out.final_state.newton_iterations;
  out.cuts = out.final_state.cuts;
  out.factorizations = out.final_state.factorizations;
  out.elements = m.element_count();
  out.history = history;
  out.sheared_ends = static_cast<bool>(warping) || static_cast<bool>(shear);
  out.equations = out.final_state.equations;
  out.flank_stiffness_N_mm4 = knobs.flank_stiffness_N_mm4;
  out.flank_stick_N_mm4 = knobs.flank_stick_N_mm4;
  flank_shares(out);
  return out;
}

void write_cycle_csv(const CycleResult& r, const std::string& path) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    if (!f) throw core::InputError("cannot write '" + path + "'");
    f.precision(9);
    f << "point,role,x_mm,y_mm,t_s,s_mm,s11_MPa,s22_MPa,s12_MPa,s33_MPa,e11,e22,e12\n";
    for (const MonitoredHistory& mh : r.points)
      for (const CycleSample& c : mh.samples) {
        for (double v : {c.s11_MPa, c.s22_MPa, c.s12_MPa, c.s33_MPa, c.e11, c.e22, c.e12})
          if (!std::isfinite(v)) throw core::NumericalError("segment cycle: non-finite value at '" + mh.point.name + "'");
        f << mh.point.name << ',' << to_string(mh.role) << ',' << mh.point.x_mm << ',' << mh.point.y_mm << ','
          << c.t_s << ',' << c.s_mm << ',' << c.s11_MPa << ',' << c.s22_MPa << ',' << c.s12_MPa << ','
          << c.s33_MPa << ',' << c.e11 << ',' << c.e22 << ',' << c.e12 << '\n';
      }
    if (!f) throw core::InputError("cannot write '" + path + "'");
  }
  std::rename(tmp.c_str(), path.c_str());
}

}  // namespace fitlib::segment
