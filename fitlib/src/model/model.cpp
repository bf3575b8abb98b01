#include "fitlib/model/model.hpp"

#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"

namespace fitlib::model {

std::vector<double> Model::default_parameters() const {
  std::vector<double> values;
  for (const auto& spec : parameters()) values.push_back(spec.default_value);
  return values;
}

std::vector<double> Model::initial_parameters(const DataSummary&) const {
  return default_parameters();
}

nlohmann::json Model::temperature_law(const double*) const {
  return {{"law", "none"}};
}

TestMode parse_test_mode(const std::string& text) {
  if (const auto mode = test_mode_from_label(text)) return *mode;
  throw core::UsageError("unknown test mode '" + text +
                         "' (expected shear, uniaxial, tension, compression or bulk)");
}

}  // namespace fitlib::model
