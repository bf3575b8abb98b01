#include "fitlib/belt/stiffness.hpp"

#include <cmath>

namespace fitlib::belt {

double cord_stiffness_N(double T, double cord_area_mm2, double E1_MPa) {
  return cord_area_mm2 * E1_MPa * (76.6 + (102.0 - T) * 0.52877);
}

double axial_modulus_MPa(double T, double E0_MPa) {
  return E0_MPa * (12.75 + (95.5 - T) * 0.62903);
}

double bending_stiffness_Nmm2(double T, double E0_MPa) {
  return E0_MPa * FritzsonConstants::bending_inertia_mm4 * (1.0 + (20.0 - T) * 0.001786);
}

double radial_stiffness_MPa(double beta, double E33_MPa, double H, double B) {
  return 10.0 * std::tan(beta) * E33_MPa * H / B;
}

}  // namespace fitlib::belt
