#pragma once
// Belt stiffnesses c, k1, EI (Report I §6.1, A.36–A.37; docs/belt.md, "Stiffness laws").
//
// The thesis normalises moduli by proprietary constants E0 (rubber) and E1 (cord). The project
// fixes them once (docs/decisions.md, "belt: E0 and E1"): E0 = 10 MPa, E1 = 100 MPa, with a cord
// area A_c = 5 mm² for the 0.500 in belt, which gives c ≈ 60 kN at 20 °C (Sorge–Cammalleri's
// S ≈ 60 kN for a belt of the same size) and EI ≈ 8.3 N·m²·1e-3 (834 mm⁴ × E0).
namespace fitlib::belt {

struct FritzsonConstants {
  static constexpr double E0_MPa = 10.0;
  static constexpr double E1_MPa = 100.0;
  static constexpr double cord_area_mm2 = 5.0;
  static constexpr double bending_inertia_mm4 = 834.0;  // EI = E0·834 at 20 °C (6.5)
  // The laws below are straight lines through material tests from room temperature to about
  // 100 °C (Report I L812–832, from Report V's tests); beyond, (6.4) falls to zero at 115.8 °C.
  static constexpr double tested_low_C = 20.0, tested_high_C = 100.0;
};

// c = A_c E1 (76.6 + (102 − T)·0.52877)  (6.1), N.
double cord_stiffness_N(double temperature_C, double cord_area_mm2 = FritzsonConstants::cord_area_mm2,
                        double E1_MPa = FritzsonConstants::E1_MPa);
// E33 = E0 (12.75 + (95.5 − T)·0.62903)  (6.4), MPa.
double axial_modulus_MPa(double temperature_C, double E0_MPa = FritzsonConstants::E0_MPa);
// EI = E0·834·(1 + (20 − T)·0.001786)  (6.5), N·mm².
double bending_stiffness_Nmm2(double temperature_C, double E0_MPa = FritzsonConstants::E0_MPa);
// k1 = 10 tan β E33 H/B  (A.37), MPa.
double radial_stiffness_MPa(double wedge_half_angle_rad, double E33_MPa, double height_mm,
                            double width_mm);

}  // namespace fitlib::belt
