#include "fitlib/model/model.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/model/material_point.hpp"

namespace fitlib::model {

std::vector<double> Model::default_parameters() const {
  std::vector<double> values;
  for (const auto& spec : parameters()) values.push_back(spec.default_value);
  return values;
}

std::vector<double> Model::initial_parameters(const DataSummary&) const {
  return default_parameters();
}

void check_strain_history(const StrainHistory& h) {
  if (h.time_s.size() != h.strain.size())
    throw core::UsageError("strain history: time and strain have different lengths");
  for (size_t n = 1; n < h.time_s.size(); ++n)
    if (!(h.time_s[n] > h.time_s[n - 1]))
      throw core::UsageError("strain history: times must increase strictly (sample " +
                             std::to_string(n) + ")");
}

void require_finite_parameters(const Model& model, const std::vector<double>& p) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!std::isfinite(p[i]))
      throw core::UsageError(model.kind() + ": parameter '" + model.parameters()[i].name + "' is not finite");
}

std::string to_string(ShiftLaw law) {
  switch (law) {
    case ShiftLaw::none: return "none";
    case ShiftLaw::wlf: return "wlf";
    case ShiftLaw::arrhenius: return "arrhenius";
    case ShiftLaw::polynomial: return "polynomial";
    case ShiftLaw::other: break;
  }
  throw core::UsageError("a model-specific temperature law has no option name");
}

ShiftLaw parse_shift_law(const std::string& name) {
  for (ShiftLaw law : {ShiftLaw::none, ShiftLaw::wlf, ShiftLaw::arrhenius, ShiftLaw::polynomial})
    if (name == to_string(law)) return law;
  throw core::UsageError("unknown temperature_law '" + name + "' (none, wlf, arrhenius, polynomial)");
}

std::string linear_factor_out_of_law(const std::string& name, double c_per_C, double reference_C,
                                     double temperature_C, double floor) {
  const double g = 1.0 - c_per_C * (temperature_C - reference_C);
  if (!std::isfinite(temperature_C) || g > floor) return {};
  // g > floor ⇔ c (T − T_ref) < 1 − floor: below the limit for c > 0, above it for c < 0.
  const double limit = reference_C + (1.0 - floor) / c_per_C;
  return "the linear temperature factor g = 1 - " + name + " (T - T_ref) is " + core::format_number(g, 4) + " at " +
         core::format_number(temperature_C) + " degC (" + name + " = " + core::format_number(c_per_C) +
         " 1/degC, T_ref " + core::format_number(reference_C) + " degC): the law describes a material only " +
         (c_per_C > 0.0 ? "below " : "above ") + core::format_number(limit, 5) + " degC";
}

nlohmann::json Model::temperature_law(const double*) const {
  return {{"law", "none"}};
}

double Model::bulk_modulus(const double*) const { return std::nan(""); }

std::shared_ptr<const MaterialPoint> Model::material_point(const double*,
                                                           const PointOptions&) const {
  throw core::UsageError("model '" + kind() + "' has no material point");
}

TestMode parse_test_mode(const std::string& text) {
  if (const auto mode = test_mode_from_label(text)) return *mode;
  throw core::UsageError("unknown test mode '" + text +
                         "' (expected shear, uniaxial, tension, compression or bulk)");
}

}  // namespace fitlib::model
