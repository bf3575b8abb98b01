// The one place that maps model names to implementations.
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/model/elastic.hpp"
#include "fitlib/model/fritzson.hpp"
#include "fitlib/model/linear.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::model {

ModelPtr make_model(const std::string& kind, const nlohmann::json& options) {
  if (is_linear_kind(kind)) return make_linear_model(kind, options);
  if (fritzson::is_fritzson_kind(kind)) return fritzson::make_fritzson_model(kind, options);
  if (is_elastic_kind(kind)) return make_elastic_model(kind, options);
  std::string known;
  for (const auto& k : model_kinds()) known += (known.empty() ? "" : ", ") + k;
  throw core::UsageError("unknown model '" + kind + "' (known: " + known + ")");
}

std::vector<std::string> model_kinds() {
  return {"prony", "zener3", "retardation", "fractional-zener", "fritzson", "fritzson-iso",
          "elastic-iso", "elastic-ortho"};
}

}  // namespace fitlib::model
