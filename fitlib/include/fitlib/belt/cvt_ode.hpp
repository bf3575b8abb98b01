#pragma once
// Sorge's 2-D shear-compliant contact region of a rubber V-belt CVT pulley (docs/belt.md,
// "Sorge 2-D CVT: contact-region ODE", Sorge §II.B Eqs 3–11), solved by shooting from the exit.
// θ is the wrap angle from the entrance (0) to the exit (Θ); primes are d/dθ. All quantities are
// dimensionless: x = penetration Δr/r∞, χ = penetration angle, ε = T/S_l, σ = S/S_l,
// m = (M/S_f + 1/r_fact) r∞(1 − x)/cos χ, thrust per S_l. See docs/belt.md for the equations.
#include <vector>
#include "fitlib/core/units.hpp"

namespace fitlib::belt {

struct CvtContactBelt {          // dimensionless groups of the contact region
  double friction = 0.4;         // f
  double k = 0.15;               // 4 tan²α E_axial h r∞²/(w̄ S_l)
  double groove_half_angle_rad = 13.0 * core::kPi / 180;  // α
  double P = 4e-5;               // S_f/(S_l r∞²)
  double s = 59000.0 / 105.0;    // S_l/S_s
  double H = 8.0 / 44.57;        // h/r∞; r∞ from k with E_z h/w̄ = 21 N/mm² (docs/belt.md)
  double W = 8.0 / 15.5;         // h/w̄
};

struct CvtContactCase {
  double exit_strain = 250.0 / 59000.0;                               // ε_out
  double exit_sliding_angle_rad = 191.0 * core::kPi / 180;  // γ_out(Z = 0), in (90°, 270°)
  double wrap_rad = core::kPi;                           // Θ
};

struct CvtOdeOptions {
  double tolerance = 1e-9;          // abs = rel tolerance of the Dormand–Prince 5(4) stepper
  double shooting_tolerance = 1e-9; // Newton stops below this scaled entrance residual
  double accept_residual = 1e-5;    // and accepts a wrap step below max(this, 30·tolerance):
                                    // x_in ≤ 1e-5 ε_out/k
  int max_newton_iterations = 60;
  double continuation_step_rad = 0.3;  // wrap continuation from the short-wrap start
  bool keep_profile = true;
};

struct CvtContactSolution {
  // Exit unknowns found by shooting and the kinematic constant they fix.
  double exit_penetration_angle_rad = 0, exit_moment = 0, kappa = 0;
  double entry_strain = 0;               // ε_in (output: the torque follows from ε_in − ε_out)
  double axial_thrust_per_Sl = 0;        // ∫ F'_axial dθ / S_l, Eq (7) integrated over Z and θ
  double residual = 0;                   // scaled entrance residual reached
  int shots = 0;                         // ODE integrations used
  std::vector<double> theta, x, chi, eps, sigma, m;  // profile, entrance → exit
};

// Shooting from the exit (x = 0, ε = ε_out, γ(0) = γ_out, σ = −m√(Pε/(1 + sε))) on (χ_out, m_out)
// until x = 0 and σ = +m√(Pε/(1 + sε)) at θ = 0 (the entrance). Continuation in the wrap from a
// short wrap. NumericalError when the shooting does not converge; InputError for bad data
// (self-locking f ≥ cot α, γ_out outside (90°, 270°), non-positive ε_out, k, P, wrap).
CvtContactSolution solve_cvt_contact(const CvtContactBelt& b, const CvtContactCase& c,
                                     const CvtOdeOptions& o = {});

// Z-integrals at one section: parallel, perpendicular = ∫ w K dZ of (8), (9) (wall force per
// k x (1 − x) S_l), moment = ∫ Z w K_∥ dZ of (11), axial = ∫ (1 − x − ZH cos χ)/(2 tan α cos χ
// (1 − 2ZW tan α)) dZ of (7) (axial force per k x S_l). Exposed for tests.
struct CvtWallKernels { double parallel, perpendicular, moment, axial; };
CvtWallKernels cvt_wall_kernels(const CvtContactBelt& b, double x, double chi, double eps,
                                double m, double kappa);

// The paper's example pulleys (Figs 4–5 data plus the §IV measurements; choices in docs/belt.md).
CvtContactBelt sorge_example_belt();
CvtContactCase sorge_example_case(bool driver);

}  // namespace fitlib::belt
