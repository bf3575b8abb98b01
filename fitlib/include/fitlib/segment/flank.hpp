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
// (the elastic level keeps LDLᵀ).
// The tangential flank (docs/segment.md "Tangential flank"): Report I's friction 6.6 is Coulomb's
// at full μ_used; where the load cycle uses less than the drive's μ (the driver exit's ramp, where
// the sliding reverses), the flank can stick. A point's offset along the cord from its column's
// cord point, w = t·(x − c), beyond its slip w_s, is held by an elastic stick
//     B_t = −k_t (w − w_s),   |B_t| ≤ (μ − μ_used) p 2/(B cos β)   (N/mm³, added to 6.6),
// k_t = 12 G / B² (the width-mean of a layer sheared between flanks held in stick, G its shear
// modulus); beyond the limit the point slips (return mapping, w_s committed per point). w = w_s
// (no motion relative to the foot) leaves Report I's friction exactly. Where the friction is fully
// used (the sliding arcs) only its direction can change: the friction turns with the point's
// velocity along the belt relative to its cord point (flank_slide_point below).
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "fitlib/segment/curve.hpp"
#include "fitlib/segment/load.hpp"
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

// k_t = 12 G / B² (N/mm⁴): a width B held at both flanks, loaded uniformly along the belt, has
// the width-mean displacement f B² / (12 G) (parabolic profile).
double flank_stick_stiffness_N_mm4(double shear_modulus_MPa, double width_mm);

// The stick law at one point: B_t along the cord tangent for the offset `w_mm` − `slip_mm` (the
// committed slip), with k_t and the limit (μ − μ_used) p 2/(B cos β) (N/mm³). Stick: −k_t (w − w_s),
// dB_t/dw = −k_t; slip (|k_t (w − w_s)| > limit): ∓limit, 0. `slip_after_mm`: the slip to commit.
struct FlankStickPoint {
  double B_t_N_mm3 = 0.0, dB_dw_N_mm4 = 0.0, slip_after_mm = 0.0;
  bool slipping = false;
};
FlankStickPoint flank_stick_point(double w_mm, double slip_mm, double k_t_N_mm4, double limit_N_mm3);

// The sliding friction's direction (docs/segment.md "Tangential flank"): Report I's friction is
// Coulomb's, −F ê with F = μ_used p 2/(B cos β) and ê = (sin γ, cos γ) the flank's sliding direction
// (along the belt, radial). With the point's own motion relative to its column's cord point, u̇ =
// (Δw, Δr)/Δt along the cord's tangent and normal, the sliding velocity is v = V ê + u̇ (V the load
// cycle's sliding speed, at least the floor V_0), and the friction follows its direction, regularised
// by V_0 where the sliding stops (g(v) = v / √(|v|² + V_0²), Coulomb's v/|v| for |v| ≫ V_0, a viscous
// stick F v / V_0 for |v| ≪ V_0). Added to the dead −F ê:
//     b = −F (g(V ê + u̇) − g(V ê)),  ∂b/∂u̇ = −F (q I − v vᵀ) / q^{3/2},  q = |v|² + V_0²,
// exactly 0 at u̇ = 0 (Report I's). Only the motion along the belt enters, u̇ = (Δw/Δt, 0): Report I's
// radial sliding already comes from the section's radial deflection in the groove (belt.md, A.5/A.20),
// its sliding along the belt from the cord's strain, not from the rubber's shear relative to the cord.
// ∂b/∂x = ∂b/∂u̇_l tᵀ / Δt in the cord's frame at λ: unsymmetric (the friction turns, so its radial
// part follows the motion along the belt).
struct FlankSlidePoint {
  Eigen::Vector2d b_lr_N_mm3 = Eigen::Vector2d::Zero();      // along the belt, radial
  Eigen::Matrix2d db_dv_lr = Eigen::Matrix2d::Zero();        // ∂b/∂u̇ (N·s/mm⁴)
};
FlankSlidePoint flank_slide_point(const Eigen::Vector2d& relative_velocity_lr_mm_s, const Eigen::Vector2d& friction_lr_N_mm3,
                                  double sliding_speed_mm_s, double floor_mm_s);

// The friction turned by the flank's compliance (docs/segment.md "Tangential flank"): Coulomb's law
// with the flank's elastic layer k_t in series (a return map onto Coulomb's circle). Report I's
// friction f = −F ê (along the belt, radial; F = μ_used p 2/(B cos β)) is Coulomb's at full slip; a
// point's motion Δw along the cord relative to its column's cord point strains the layer, which
// turns the friction on the circle |f| = F:
//     d = c (d_n − k_t Δw),   f' = F q / |q|,   q = f + (d, 0),   c = F / (F + k_t V Δt),
// d the layer's force along the belt (N/mm³, per point, committed), relaxed by the load cycle's
// sliding V Δt over the increment (the backward-Euler return onto the circle of the slip V Δt ê:
// a Maxwell element of k_t and F/V, a stick where V = 0). Added to the dead −F ê: b = f' − f, exactly
// 0 at d = 0. ∂b/∂w = −c k_t F/|q| (I − n nᵀ) (1, 0)ᵀ, n = q/|q|: unsymmetric (the turn moves the
// radial part too). A turn along the sliding direction itself does not change f (Coulomb).
struct FlankTurnPoint {
  Eigen::Vector2d b_lr_N_mm3 = Eigen::Vector2d::Zero();   // along the belt, radial
  Eigen::Vector2d db_dw_lr_N_mm4 = Eigen::Vector2d::Zero();
  double layer_after_N_mm3 = 0.0;  // d, to commit
};
FlankTurnPoint flank_turn_point(double dw_mm, double layer_N_mm3, const Eigen::Vector2d& friction_lr_N_mm3,
                                double k_t_N_mm4, double slide_mm);

// Per element at λ: the radial foundation's k (N/mm⁴), the stick's k_t (N/mm⁴) and its limit (N/mm³),
// Report I's dead friction −F ê (along the belt, radial; N/mm³) with the sliding speed V (mm/s,
// floored) for the sliding friction's direction; 0: that part off there. `time_s`: the time at λ.
// Sized to the elements by the caller.
struct FlankLevels {
  std::vector<double> radial_N_mm4, stick_N_mm4, stick_limit_N_mm3, slide_mm_s, turn_N_mm4;
  std::vector<Eigen::Vector2d> friction_lr_N_mm3;
  double slide_floor_mm_s = 0.0;  // V_0
  double time_s = 0.0;
};

// The radial foundation, the stick and the sliding friction's direction together as one load acting
// at the integration points (segment/load.hpp), with a commit for the slip. `stick`, `slide`: whether the stick
// or the sliding friction's direction is on at all (the frames are then prepared at every λ and
// each point's offset committed, so a point starts from its offset where they begin; `slide` makes
// the tangent unsymmetric); `levels(λ, levels)`: the per-element values at λ.
LoadPtr flank_contact(const Mesh& reference, const std::vector<double>& path_x_mm, Integration integration,
                      const NeutralCurve& reference_curve, std::function<NeutralCurve(double lambda)> curve_at,
                      bool stick, bool slide, bool turn, std::function<void(double lambda, FlankLevels& levels)> levels);

// The foundation over a mesh as a load acting at the integration points (segment/load.hpp).
// `reference`: the solver's mesh; `path_x_mm`: each node's unstrained path position along the cord
// (its x in the straight section); `reference_curve`: the cord curve of the reference, against
// which h_ref is measured (the mould circle); `curve_at(λ)`: the cord curve at λ; `stiffness(λ, k)`:
// k per element at λ (0: none; the load cycle's: k where p > 0).
LoadPtr flank_foundation(const Mesh& reference, const std::vector<double>& path_x_mm, Integration integration,
                         const NeutralCurve& reference_curve, std::function<NeutralCurve(double lambda)> curve_at,
                         std::function<void(double lambda, std::vector<double>& k_N_mm4)> stiffness);

}  // namespace fitlib::segment
