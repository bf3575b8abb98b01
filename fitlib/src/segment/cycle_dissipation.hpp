#pragma once
// The energy the rubber dissipates over the last load cycle (docs/thermal.md §1, complete level):
// the stress work ∮ P : dF = ∮ S : dE per unit reference volume at every integration point
// (trapezoidal in S : dE over the converged increments, an element's mean over its points times its reference area), summed
// over the central two pitches, per mm of belt length. The load cycle is periodic by then, so each
// point's stored energy returns and the work is what its material dissipated — for every model
// alike (an elastic point gives zero), with no model-specific code (docs/decisions.md
// "Complete-level hysteresis: the last cycle's stress work").
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/LU>

#include "cycle_observers.hpp"

namespace fitlib::segment::detail {

class CycleDissipation : public IncrementObserver {
 public:
  // `area_mm2`, `centre_x_mm`: per element; `pitch_mm`: the cog pitch; `out`: J per mm of belt
  // length and cycle, per role (CycleResult::dissipation_J_mm).
  CycleDissipation(const CycleFrame& frame, std::vector<double> area_mm2, const std::vector<double>& centre_x_mm,
                   double pitch_mm, double width_mm, std::array<double, 2>& out)
      : frame_(frame), area_(std::move(area_mm2)), out_(out) {
    for (std::size_t e = 0; e < area_.size(); ++e)
      if (!(std::abs(centre_x_mm[e]) < pitch_mm)) area_[e] = 0.0;  // the central two pitches only
    scale_ = width_mm * 1e-3 / (2.0 * pitch_mm);                  // N mm per mm width → J per mm of belt
  }

  void converged(double lambda, const StaticSolution& s) override {
    // The last cycle, τ ∈ [T − 1, T], after the bend (a run shorter than a cycle: cycle_split.hpp).
    const double tau = frame_.tau(lambda), start = std::max(1.0, frame_.T - 1.0);
    if (!last_.empty() && tau > start) {
      const double share = std::min(1.0, (tau - start) / (tau - tau_));  // an increment across the start counts in part
      for (std::size_t e = 0; e < area_.size(); ++e) {
        if (area_[e] == 0.0) continue;
        double w = 0.0;
        for (std::size_t g = 0; g < s.points[e].size(); ++g) {
          const State now = state(s.points[e][g]), &was = last_[e][g];
          w += (0.5 * (was.S + now.S).cwiseProduct(now.E - was.E)).sum();
        }
        out_[static_cast<int>(frame_.mesh->roles[e])] += share * w / s.points[e].size() * area_[e] * scale_;
      }
    }
    tau_ = tau;
    last_.resize(s.points.size());
    for (std::size_t e = 0; e < s.points.size(); ++e) {
      last_[e].resize(s.points[e].size());
      for (std::size_t g = 0; g < s.points[e].size(); ++g) last_[e][g] = state(s.points[e][g]);
    }
  }

 private:
  // The second Piola–Kirchhoff stress S = F⁻¹ P and the Green–Lagrange strain E = ½ (FᵀF − I):
  // S : dE = P : dF, and a rigid rotation changes neither, so the trapezoidal rule adds no work
  // where the segment turns onto a pulley (P : ΔF of a stressed, rotating point does).
  struct State {
    Eigen::Matrix2d S, E;
  };
  static State state(const IntegrationPointStress& ip) {
    return {ip.F.inverse() * ip.piola_MPa, 0.5 * (ip.F.transpose() * ip.F - Eigen::Matrix2d::Identity())};
  }
  const CycleFrame& frame_;
  std::vector<double> area_;
  double scale_ = 0.0, tau_ = 0.0;
  std::vector<std::vector<State>> last_;
  std::array<double, 2>& out_;
};

}  // namespace fitlib::segment::detail
