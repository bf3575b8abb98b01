#pragma once
// Viscoelastic belts after Sorge & Cammalleri (AIMETA 2001; docs/belt.md, "Sorge–Cammalleri"): the
// three-parameter belt T + τ_T Ṫ = S(ε + τ_ε ε̇) (1) in the tension test on two pulleys and in a
// steady two-pulley drive. Forces N, angles rad, times s.
#include <vector>

namespace fitlib::belt {

struct ThreeParameterBelt {
  double S_N = 60000.0;   // equilibrium stiffness S
  double tau_T_s = 27.0;  // relaxation-side time τ_T
  double tau_eps_s = 40.0;  // creep-side time τ_ε
};

// Tension test, loading at constant rate v (mm/s) from rest: b = d0 + 2r[1 − e^{−fπ/2}]/f (3) and
// T(t, θ) = S v {t + (τ_ε − τ_T)[1 − e^{−t/τ_T}]} e^{−fθ}/b — Eq. (4) with the exponent derived
// from (1) with T(0) = 0 (the printed e^{−t/τ_ε} is a typo; docs/decisions.md).
double tension_test_b_mm(double d0_mm, double r_mm, double f);
double tension_test_loading_N(const ThreeParameterBelt& m, double v_mm_s, double b_mm, double t_s,
                              double theta_rad, double f);
// The printed Eq. (4), kept to show in tests that it does not solve (1).
double tension_test_loading_as_printed_N(const ThreeParameterBelt& m, double v_mm_s, double b_mm,
                                         double t_s, double theta_rad, double f);
// Relaxation after a held elongation: T − T∞ = (T_x − T∞) e^{−t/τ_T}.
double relaxation_N(const ThreeParameterBelt& m, double T_x_N, double T_inf_N, double t_s);
// Free-span force from (1) integrated in time for a given elongation history ε(t) (sampled,
// piecewise linear, exact exponential integrator): an independent check of the closed forms.
std::vector<double> integrate_three_parameter(const ThreeParameterBelt& m,
                                              const std::vector<double>& t_s,
                                              const std::vector<double>& eps, double T0_N = 0.0);

// Load/unload test simulated in time (Eqs 2–9): a quarter wrap θ ∈ [0, π/2] (θ from the span
// end) on `nodes` points, the free span, and the geometric condition (2)/(8) solved for the span
// tension at every step. Loading (rate +v for load_time_s): every element slides outward,
// T = T_fs e^{−fθ}. Unloading (rate −v until the span tension reaches zero or d = d0): a sliding
// arc θ < θ_b(t) with T = T_fs e^{+fθ} spreads from the span end while the rest adheres with its
// elongation frozen and its tension relaxing by (1); θ_b is where the two tensions meet (6).
// Each element's elongation follows (1) exactly for piecewise-linear tension.
struct TensionTestInput {
  ThreeParameterBelt belt;
  double d0_mm = 250.0, r_mm = 39.0, f = 0.12;
  double v_mm_s = 10.0 / 60.0;  // 10 mm/min
  double load_time_s = 120.0;
  int nodes = 400, steps_per_phase = 1200;
};
struct TensionTestPoint {
  double t_s = 0.0, elongation_mm = 0.0, span_tension_N = 0.0, boundary_rad = 0.0;
};
struct TensionTestResult {
  std::vector<TensionTestPoint> loading, unloading;
};
TensionTestResult simulate_tension_test(const TensionTestInput& in);

// Steady drive on two equal pulleys (the paper's Fig 5 case by default), belt speed v, pulley
// angular speed ω = v/r. Per pulley: entrance sliding arc θ_e (≥ 0), adhesion arc θ_a, main
// sliding arc θ_s; regions solved piecewise with Eqs (10a,b), matched in T and ε, and the loop
// closed on ε (the conditions the paper writes as Eqs 17, 19, 20).
struct ViscoelasticDriveInput {
  ThreeParameterBelt belt;
  double tight_N = 500.0, slack_N = 200.0;  // dynamic tensions (T − qv²)
  double radius_mm = 40.0, center_distance_mm = 250.0, friction = 0.5;
  double omega_rad_s = 100.0;
  int steps_per_rad = 2000;  // march resolution in the sliding arcs
};
struct ViscoelasticPulley {
  double entrance_sliding_rad = 0.0, adhesion_rad = 0.0, main_sliding_rad = 0.0;
  double adhesion_elongation = 0.0;       // ε_R or ε_N
  double max_relative_slip = 0.0;         // max |ε − ε_adhesion| on the main arc (∝ sliding speed)
  std::vector<double> theta_rad, T_N, eps;  // profile over the wrap
};
struct ViscoelasticDrive {
  ViscoelasticPulley driver, driven;
  int iterations = 0;
};
// InputError (key viscoelastic...) for a belt that slips or non-positive data.
ViscoelasticDrive solve_viscoelastic_drive(const ViscoelasticDriveInput& in);

// The belt in a running drive: equilibrium stiffness S with the short drive-time constants of
// Sorge–Cammalleri's "crude extrapolation" (seed L162), τ_T ≈ 0.2/ω, τ_ε ≈ 0.3/ω, ω the pulley's
// angular speed (rad/s).
ThreeParameterBelt drive_time_belt(double S_N, double omega_rad_s);

// The paper's route: the six matching equations (17a,b) tension at the exits, (19a,b) elongation
// continuity at the entrances through the free spans, (20a,b) |T'| = fT where adhesion starts, in
// θ_eR, θ_sR, θ_eN, θ_sN, ε_R, ε_N, solved with Ceres under θ_e ≥ 0. An entrance arc that ends on
// its bound θ_e = 0 drops its equation (20) (the paper sets negative widths to zero) and the rest
// is solved again. Independent of the march above; tests compare the two.
struct ViscoelasticEquations {
  double entrance_R = 0, sliding_R = 0, entrance_N = 0, sliding_N = 0, eps_R = 0, eps_N = 0;
  double max_residual_N = 0;  // largest residual of the equations kept, in N
};
ViscoelasticEquations solve_viscoelastic_equations(const ViscoelasticDriveInput& in);

}  // namespace fitlib::belt
