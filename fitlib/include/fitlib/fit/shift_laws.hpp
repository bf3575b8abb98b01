#pragma once
// Given shift factors (a pyvisco shift file) instead of fitted ones, pyvisco's polynomial shift
// law, and cards that carry a temperature law fitted to shifts (docs/fitting.md, "Shift-factor
// files and the polynomial law").
#include <string>
#include <vector>

#include "fitlib/data/relaxation.hpp"
#include "fitlib/data/shift_factors.hpp"
#include "fitlib/fit/master_curve.hpp"

namespace fitlib::fit {

// log10 a_T = Σ_{k=1..degree} C_k (T − T_ref)^k, least squares through log a_T(T_ref) = 0.
struct PolynomialShiftFit {
  std::vector<double> coefficients;  // C_1 … C_degree, units 1/K^k
  double rms_decades = 0.0;
};
PolynomialShiftFit fit_polynomial_shift(const std::vector<double>& temperatures_C,
                                        const std::vector<double>& log10_aT, double reference_C, int degree);

// log10 a_T of `shifts` at T, re-referenced so that log10 a_T(reference_C) = 0 (linear
// interpolation in T; InputError beyond the table by more than 0.5 °C).
double given_log10_aT(const data::ShiftFactorTable& shifts, double temperature_C, double reference_C);

// Raw isotherms grouped as build_master_curve does, shifted by the given factors; the pair
// figures (found for the model-free shifts) are cleared, WLF and Arrhenius refitted.
MasterCurve master_curve_from_shift_factors(const data::DynamicTestTable& raw, const data::ShiftFactorTable& shifts,
                                            double reference_C);

// Relaxation rows at reduced time t / a_T, temperature = reference_C.
data::RelaxationTable shift_relaxation_table(const data::RelaxationTable& raw, const data::ShiftFactorTable& shifts,
                                             double reference_C);

// The model of `result` (fitted at T_ref without a law) with temperature law `law` (wlf or
// polynomial) at reference_C, its constants fitted to the shift points and held fixed in the
// slots the model names (Model::temperature_law_info). A law whose rms misfit to the shifts
// exceeds kShiftLawWarnDecades adds a quality warning.
inline constexpr double kShiftLawWarnDecades = 0.2;  // a factor 1.6 in frequency
FitResult with_law_from_shifts(const FitResult& result, const std::vector<double>& temperatures_C,
                               const std::vector<double>& log10_aT, double reference_C, model::ShiftLaw law,
                               int polynomial_degree = 3);

// The isotherm shifts of a master curve as a pyvisco shift-factor table.
data::ShiftFactorTable shift_factors_of(const MasterCurve& curve);

}  // namespace fitlib::fit
