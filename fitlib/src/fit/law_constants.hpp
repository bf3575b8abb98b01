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
  std::vector<std::string> held_at_bound;  // "C1 1131.75 held at 1000": the free fit passed a bound
};

// WLF (≥ 3 shifts), Arrhenius (≥ 2), polynomial of `polynomial_degree` (≥ degree shifts);
// core::UsageError otherwise. `bounds`: the specs of the model's law constants (in order); the
// constants are the best fit inside them, so the card holding them reads back (empty: free).
LawConstants fit_law_constants(model::ShiftLaw law, const std::vector<double>& temperatures_C,
                               const std::vector<double>& log10_aT, double reference_C, int polynomial_degree,
                               const std::vector<core::ParameterSpec>& bounds = {});

}  // namespace fitlib::fit::detail
