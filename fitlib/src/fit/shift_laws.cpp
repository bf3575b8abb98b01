// Given shift factors (a pyvisco shift file) instead of fitted ones: the master curve and the
// relaxation rows they shift, and a curve's shifts as such a table.
#include "fitlib/fit/shift_laws.hpp"

#include <cmath>

#include "fitlib/core/error.hpp"

namespace fitlib::fit {

double given_log10_aT(const data::ShiftFactorTable& shifts, double temperature_C, double reference_C) {
  return data::interpolate_log10_aT(shifts, temperature_C) - data::interpolate_log10_aT(shifts, reference_C);
}

MasterCurve master_curve_from_shift_factors(const data::DynamicTestTable& raw, const data::ShiftFactorTable& shifts,
                                            double reference_C) {
  MasterCurveOptions options;
  options.reference_C = reference_C;
  MasterCurve curve = build_master_curve(raw, options);
  std::vector<double> log10_aT;
  for (auto& iso : curve.isotherms) {
    log10_aT.push_back(given_log10_aT(shifts, iso.temperature_C, reference_C));
    iso.pair_rms_decades = std::nan("");
    iso.pair_overlap_points = 0;
  }
  apply_shifts(curve, raw, log10_aT);
  curve.messages.push_back("shifts from " + shifts.source_file + " (interpolated at the isotherm temperatures)");
  return curve;
}

data::RelaxationTable shift_relaxation_table(const data::RelaxationTable& raw, const data::ShiftFactorTable& shifts,
                                             double reference_C) {
  data::RelaxationTable out = raw;
  for (auto& row : out.rows) {
    if (std::isnan(row.temperature_C))
      throw core::InputError("row without a temperature cannot be shifted", row.source_file, row.source_line);
    row.time_s /= std::pow(10.0, given_log10_aT(shifts, row.temperature_C, reference_C));
    row.temperature_C = reference_C;
  }
  return out;
}

data::ShiftFactorTable shift_factors_of(const MasterCurve& curve) {
  data::ShiftFactorTable t;
  t.reference_C = curve.reference_C;
  for (const auto& iso : curve.isotherms) t.factors.push_back({iso.temperature_C, iso.log10_aT});
  return t;
}

}  // namespace fitlib::fit
