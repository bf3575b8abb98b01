#pragma once
// Sliding contact of a V-belt on one pulley (Report I, Appendix A; docs/belt.md, "Equations as implemented").
//
// A sliding arc starts at the reference point P (end of the non-sliding arc, γ = 180°) and runs
// with φ in the direction of belt travel. κ = F/F_P; x0 = x/R is the radial sinking of the belt.
// Two solutions: the closed forms (A.25–A.35) and the full ODE (A.15, A.17, A.22) integrated
// with Boost.Odeint from a series start at P. The ODE depends only on μ, β and c0.
#include <vector>
#include "fitlib/core/units.hpp"

namespace fitlib::belt {

enum class PulleyRole { driver, driven, idler };
const char* to_string(PulleyRole role);

struct ArcParameters {
  double friction = 0.8;              // μ
  double wedge_half_angle_rad = 0.33;  // β, half the included groove angle
  double c0 = 0.05;                   // c/(R² k1) (A.36)
  PulleyRole role = PulleyRole::driven;  // driver or driven (idler has no sliding arc)
};

// Throws core::InputError (key conditions.friction / belt.wedge_half_angle_deg) for parameters
// outside the model: μ < 0, β ∉ (0, 90°), c0 ≤ 0, and self-locking μ ≥ cot β (the wedge holds
// the belt: x0P/F0P = cot(β + arctan μ) ≤ 0).
void validate(const ArcParameters& a);

// x0P/F0P = cot(β + arctan μ) (A.23).
double sinking_ratio_at_P(const ArcParameters& a);
// f(γ) = x0/(κ F0P) (A.17) and its derivative with respect to γ.
double sinking_function(const ArcParameters& a, double gamma_rad);
double sinking_function_derivative(const ArcParameters& a, double gamma_rad);
// κ'/κ (A.15).
double force_log_slope(const ArcParameters& a, double gamma_rad);
// γ'_P: root of (A.24), positive for the driver, negative for the driven pulley.
double sliding_angle_slope_at_P(const ArcParameters& a);
// Asymptotic sliding angle γ_a of the driven pulley (A.27–A.30), in (π/2, π).
double asymptotic_sliding_angle(const ArcParameters& a);
// Capstan law with wedge factor: F_tight/F_slack = exp(μ α / sin β), the full-slip limit.
double capstan_ratio(double friction, double wrap_rad, double wedge_half_angle_rad);

// One point of a sliding arc.
struct ArcPoint {
  double phi_rad = 0.0;
  double kappa = 1.0;      // F/F_P
  double gamma_rad = 0.0;  // sliding angle
  double x0_over_F0P = 0.0;  // x0/F0P = κ f(γ)
};

// Closed forms. kappa(φ) and gamma(φ) of the sliding arc; sliding_arc_length returns the φ_S at
// which κ reaches `kappa_end` (F_out/F_P), or a negative value when the closed form cannot
// reach it (driver: γ'_P φ > π, A.32 note).
class ClosedFormArc {
 public:
  explicit ClosedFormArc(const ArcParameters& a);
  ArcPoint at(double phi_rad) const;
  double sliding_arc_length(double kappa_end) const;
  double gamma_prime_P() const { return gamma_prime_P_; }

 private:
  ArcParameters a_;
  double gamma_prime_P_ = 0.0;
  double gamma_a_ = 0.0, mu_fa_ = 0.0, mu_fP_ = 0.0;  // driven
  double mu_e_ = 0.0;                                 // driver
};

// Sliding angle limit of the driver (A.35): 273°.
constexpr double kDriverSlidingAngleLimit_rad = 273.0 * core::kPi / 180.0;

// The full ODE from P: integrates until κ reaches kappa_end or φ reaches phi_max, whichever comes
// first, with relative/absolute tolerance `tolerance`. The driver's γ is held at γ_Lim once it
// gets there (A.35). Points are the accepted steps plus the end point.
struct OdeArc {
  std::vector<ArcPoint> points;
  bool reached_kappa_end = false;
  double phi_end_rad = 0.0;  // φ_S when reached, else phi_max
};
OdeArc integrate_sliding_arc(const ArcParameters& a, double kappa_end, double phi_max_rad,
                             double tolerance = 1e-10);
// Interpolates an OdeArc at φ (linear in the stored steps; the steps are dense near P).
ArcPoint interpolate(const OdeArc& arc, double phi_rad);

}  // namespace fitlib::belt
