#pragma once
// The pieces a load-cycle run is composed of (cycle.cpp): the moulded reference, the cord curve at
// pseudo time τ, and the loads of Report I §5–§6 — contact pressure, friction and radial inertia
// as body forces (6.6–6.9), the sheared end faces, the flank's levels.
#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "fitlib/belt/load_history.hpp"
#include "fitlib/segment/curve.hpp"
#include "fitlib/segment/cycle.hpp"
#include "fitlib/segment/flank.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/static_case.hpp"

namespace fitlib::segment::detail {

// The straight mesh wrapped on the mould circle (curvature K_m, unstrained cord line): the
// stress-free reference of the moulded belt.
Mesh wrapped(const Mesh& straight, double K_m);

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
// state; step 2 reads the history at s0 + ξ, s0 = (τ − 1) L, n intervals per side over reach_mm.
NeutralCurve cord_curve(double tau, const belt::LoadHistory& history, const CurvatureIntegral& integral, double K_m,
                        double reach_mm, int n);

// The mean of load(state) over element e's path extent with the segment's middle at s0: sampled
// every `sampling_mm` (CyclePhysics::body_force_sampling_mm, the midpoint rule), or at the element's
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

using LoadAt = std::function<void(double lambda, std::vector<Eigen::Vector2d>& per_item)>;
using CurveAt = std::function<NeutralCurve(double lambda)>;

// The contact body forces per element at load level λ (global, 6.6–6.9): their mean over the
// element's path extent (ElementSampling), turned by the cord's tangent at its centre.
LoadAt contact_body_forces(ElementSampling sampling, const CycleDrive& drive, double T, CurveAt curve_at);

// The sheared end condition: each face warped and sheared as a long belt's section under the
// friction and the changes of strain and curvature at the face's path position, each smoothed by
// the shear lag (segment/end_faces.hpp); tabulated once over the cycle.
void long_belt_ends(const CogSection& section, const Mesh& straight, const std::array<const PlaneStrainLaw*, 2>& laws,
                    const CycleDrive& drive, CyclePhysics::EndProfile& warping, CyclePhysics::EndProfile& shear);
// The sheared faces' warping as the constraints' shift along the cord tangent (none in step 1).
EndShift end_shift(const Mesh& straight, const belt::LoadHistory& history, double T,
                   const CyclePhysics::EndProfile& warping);
// The faces' shear traction as dead nodal forces along each end's radial line (none in step 1).
LoadAt end_shear_forces(int nodes, const Mesh& straight, const std::vector<double>& path_x,
                        const belt::LoadHistory& history, double T, CurveAt curve_at, CyclePhysics::EndProfile shear);

// The flank's levels per element at λ (segment/flank.hpp): the radial k and the stick's k_t times
// the share of the element's path extent in a sheave (p > 0), so they engage continuously as a
// pulley's entrance passes, and the stick's limit, the unused friction (μ − μ_used) p 2/(B cos β)
// averaged over the extent (the area factor of 6.6).
// The sliding friction's direction: Report I's friction (l, r) averaged over the extent and the
// sliding speed, at least the floor V_0.
std::function<void(double, FlankLevels&)> flank_levels(ElementSampling sampling, const CycleDrive& drive,
                                                       const CyclePhysics& physics, double T,
                                                       std::function<double(double)> time_s);

}  // namespace fitlib::segment::detail
