#pragma once
// The deformation-limited flank contact (docs/segment.md "Flank foundation"; issue 11, the complete
// level's fold). Report I applies the sheave flank's pressure p, its friction and the radial
// inertia as dead body forces (6.6–6.9). Here the radial part also follows each point's depth in
// the groove: a point that moves radially inwards, deeper below the cord line by δ = h − h_ref,
// meets the flanks (half angle β) δ tan β further in on each side, so the lateral interference
// across the width B grows by 2δ tan β, the pressure by E_w 2δ tan β / B (E_w the belt's lateral
// modulus) and the radial body force 6.7 (without friction) by that times 2 tan β / B:
//     B_r = B_r,dead + k (h − h_ref),   k = 4 E_w tan²β / B²   (N/mm⁴),
// a Winkler foundation along the cord curve's normal, linearised about Report I's load. It is the
// gradient field of the energy ½ k (h − h_ref)² per reference volume, so its tangent is symmetric
// (the elastic level keeps LDLᵀ); the friction 6.6 stays Report I's (dead).
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "fitlib/segment/curve.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/solver.hpp"

namespace fitlib::segment {

// k = 4 E_w tan²β / B² (N/mm⁴) from the lateral modulus E_w (MPa), the wedge half angle β and the width B.
double flank_stiffness_N_mm4(double lateral_modulus_MPa, double wedge_half_angle_rad, double width_mm);

// The foundation at one point: its foot on the current cord curve `at` (NeutralCurve::coordinates,
// h below the curve) and its depth h_ref in the reference. b = k (h − h_ref) n, n = (sin φ, cos φ)
// the curve's outward normal at the foot (global, N/mm³), and
// ∂b/∂x = −k n nᵀ + k (h − h_ref) K t tᵀ / (1 − K h), t = (cos φ, −sin φ), K the foot's curvature.
struct FlankFoundationPoint {
  Eigen::Vector2d b_N_mm3 = Eigen::Vector2d::Zero();
  Eigen::Matrix2d db_dx_N_mm4 = Eigen::Matrix2d::Zero();
};
FlankFoundationPoint flank_foundation_point(const CurveCoordinates& at, double reference_depth_mm, double k_N_mm4);

// The foundation over a mesh as the solver's following force (StaticProblem::following_force).
// `reference`: the solver's mesh; `path_x_mm`: each node's unstrained path position along the cord
// (its x in the straight section); `reference_curve`: the cord curve of the reference, against
// which h_ref is measured (the mould circle); `curve_at(λ)`: the cord curve at λ; `stiffness(λ, k)`:
// k per element at λ (0: none; the load cycle's: k where p > 0).
StaticProblem::FollowingForce flank_foundation(const Mesh& reference, const std::vector<double>& path_x_mm,
                                               Integration integration, const NeutralCurve& reference_curve,
                                               std::function<NeutralCurve(double lambda)> curve_at,
                                               std::function<void(double lambda, std::vector<double>& k_N_mm4)> stiffness);

}  // namespace fitlib::segment
