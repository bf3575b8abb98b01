#pragma once
// Axial thrust of a rubber V-belt CVT pulley: Sorge's practical formulary (docs/belt.md,
// "Sorge CVT", Sorge Eqs 11–12). Forces N, angles rad; α is the groove half-angle.
// R = driver, N = driven; T_T, T_S = tight and slack dynamic tensions (N − μv²).
#include "fitlib/core/units.hpp"

namespace fitlib::belt {

struct CvtFormulary {  // the paper's constants for its CVT belt
  double xi_R = 2.2, xi_N = 1.5, xi_N_unseat = 2.0;
  int n = 5;
  double seat_rad = core::kPi / 6, unseat_rad = core::kPi / 18;
};

// Axial force per unit wrap angle at θ from the entrance (Eq 11), for wrap Θ.
double driver_axial_thrust_density_N(double theta, double wrap, double T_T, double alpha,
                                     const CvtFormulary& c = {});
double driven_axial_thrust_density_N(double theta, double wrap, double T_T, double T_S,
                                     double alpha, const CvtFormulary& c = {});
// Totals (Eq 12a,b): F_R ≈ T_T/(4.4 tan α)(Θ_R − 2π/27);
// F_N ≈ T_S/(3 tan α)(Θ_N − π/9) + πT_T/(108 tan α) + (3T_T − 4T_S)/(72 tan α)(Θ_N − 2π/9).
// InputError (key cvt...) when the wrap is shorter than seating + unseating.
double driver_axial_thrust_N(double T_T, double alpha, double wrap);
double driven_axial_thrust_N(double T_T, double T_S, double alpha, double wrap);

}  // namespace fitlib::belt
