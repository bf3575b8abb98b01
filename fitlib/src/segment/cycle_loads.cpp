// The loads of a load-cycle run (cycle_parts.hpp): Report I's contact body forces (6.6–6.9), the
// sheared end faces, the flank's levels.
#include <algorithm>
#include <cmath>

#include "cycle_parts.hpp"
#include "fitlib/core/quadrature.hpp"
#include "fitlib/segment/end_faces.hpp"

namespace fitlib::segment::detail {
namespace {


// A face node's share of a traction t(h) on the end face: Σ over its edges ∫ N_a t dl by 3-point
// Gauss, written as t at the Gauss points' depths times weights (one entry per node and point).
struct FaceWeight {
  int node;
  double depth_mm, length_mm;
};

std::vector<FaceWeight> face_weights(const Mesh& straight, const std::vector<int>& face) {
  std::vector<FaceWeight> out;
  const int step = straight.nodes_per_element == 8 ? 2 : 1;
  for (std::size_t a = 0; a + step < face.size(); a += step) {
    const double ya = straight.X[face[a]].y(), yb = straight.X[face[a + step]].y(), half = 0.5 * std::abs(ya - yb);
    for (const core::QuadraturePoint& g : core::gauss_legendre_3(-1.0, 1.0)) {
      const double x = g.x, depth = -(0.5 * (ya + yb) + 0.5 * x * (yb - ya));
      const double N2[3] = {0.5 * x * (x - 1.0), 1.0 - x * x, 0.5 * x * (x + 1.0)}, N1[2] = {0.5 * (1.0 - x), 0.5 * (1.0 + x)};
      for (int k = 0; k <= step; ++k)
        out.push_back({face[a + k], depth, (step == 2 ? N2[k] : N1[k]) * g.weight * half});
    }
  }
  return out;
}

}  // namespace

// The sheared end condition: each face warped and sheared as a long belt's section under the
// friction and the changes of strain and curvature at the face's path position, each smoothed by
// the shear lag (segment/end_faces.hpp); tabulated once over the cycle.
void long_belt_ends(const CogSection& section, const Mesh& straight, const std::array<const PlaneStrainLaw*, 2>& laws,
                    const CycleDrive& drive, CyclePhysics::EndProfile& warping, CyclePhysics::EndProfile& shear) {
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
EndShift end_shift(const Mesh& straight, const belt::LoadHistory& h, double T, const CyclePhysics::EndProfile& warping) {
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
    std::function<NeutralCurve(double)> curve_at, CyclePhysics::EndProfile shear) {
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
                                                       const CyclePhysics& physics, double T, std::function<double(double)> time_s) {
  const belt::LoadHistory& h = *drive.history;
  const double k = physics.flank_stiffness_N_mm4, k_t = physics.flank_stick_N_mm4, mu = drive.friction;
  const double V0 = physics.flank_slide_floor_mm_s, k_turn = physics.flank_turn_N_mm4;
  const double area_factor = 2.0 / drive.width_mm / std::cos(drive.wedge_half_angle_rad);
  return [=, &h](double lambda, FlankLevels& levels) {
    const double tau = lambda * T;
    const std::size_t n = sampling.centre_x.size();
    for (auto* v : {&levels.radial_N_mm4, &levels.stick_N_mm4, &levels.stick_limit_N_mm3, &levels.slide_mm_s,
                    &levels.turn_N_mm4})
      v->assign(n, 0.0);
    levels.friction_lr_N_mm3.assign(n, Eigen::Vector2d::Zero());
    levels.time_s = time_s(lambda), levels.slide_floor_mm_s = V0;
    if (tau <= 1.0) return;
    const double s0 = (tau - 1.0) * h.length_mm();
    for (std::size_t e = 0; e < n; ++e) {
      const int el = static_cast<int>(e);
      const double share = sampling.mean(h, el, s0, 0.0, [](const belt::LoadState& q) { return q.p_MPa > 0.0 ? 1.0 : 0.0; });
      if (k > 0.0) levels.radial_N_mm4[e] = k * share;
      if (k_turn > 0.0) levels.turn_N_mm4[e] = k_turn * share;
      if ((V0 > 0.0 || k_turn > 0.0) && share > 0.0) {
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

}  // namespace fitlib::segment::detail
