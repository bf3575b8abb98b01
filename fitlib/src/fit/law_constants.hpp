#pragma once
// Private to the fit module: a temperature law's constants fitted to isotherm shifts.
#include <string>
#include <vector>

#include "fitlib/model/model.hpp"

namespace fitlib::fit::detail {

// The law's constants, in the order of TemperatureLawInfo::shift_parameters.
struct LawConstants {
  std::vector<double> values;
  std::string summary;
  double rms_decades = 0.0;
};

// WLF (≥ 3 shifts), Arrhenius (≥ 2), polynomial of `polynomial_degree` (≥ degree shifts);
// core::UsageError otherwise.
LawConstants fit_law_constants(model::ShiftLaw law, const std::vector<double>& temperatures_C,
                               const std::vector<double>& log10_aT, double reference_C, int polynomial_degree);

}  // namespace fitlib::fit::detail
