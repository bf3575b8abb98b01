#include "fitlib/card/from_fit.hpp"

#include <cmath>

#include "fitlib/card/conversion.hpp"
#include "fitlib/card/data_window.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib::card {
namespace {

// A card holds finite numbers only: a figure that does not exist (an infinite condition number,
// the AIC of an exact fit) is left out rather than written as null.
void drop_non_finite(nlohmann::json& j) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end();) {
      if (it->is_number_float() && !std::isfinite(it->get<double>())) it = j.erase(it);
      else drop_non_finite(*it++);
    }
  } else if (j.is_array()) {
    for (auto& x : j) {
      if (x.is_number_float() && !std::isfinite(x.get<double>())) x = nullptr;
      else drop_non_finite(x);
    }
  }
}

nlohmann::json quality_json(const fit::QualityVerdict& q) {
  nlohmann::json figures = nlohmann::json::array();
  for (const auto& f : q.figures)
    figures.push_back({{"group", f.group}, {"modulus", f.modulus}, {"count", f.count},
                       {"mean_rel_error", f.mean_rel_error}, {"max_rel_error", f.max_rel_error},
                       {"max_at_frequency_Hz", f.max_at_frequency_Hz}});
  nlohmann::json j = {{"acceptable", q.acceptable()}, {"warnings", q.warnings}, {"figures", figures}};
  if (!q.kramers_kronig_ranges_Hz.empty()) {
    nlohmann::json ranges = nlohmann::json::array();
    for (const auto& [lo, hi] : q.kramers_kronig_ranges_Hz) ranges.push_back({lo, hi});
    j["kramers_kronig_inconsistent_Hz"] = ranges;
  }
  return j;
}

// fit.confidence_band: columns over frequency (docs/formats.md §3).
nlohmann::json band_json(const fit::ConfidenceBand& band) {
  nlohmann::json j = {{"level", 0.95}, {"mode", model::to_string(band.condition.mode)}};
  if (band.condition.has_temperature()) j["temperature_C"] = band.condition.temperature_C;
  const auto column = [&](auto member) {
    nlohmann::json c = nlohmann::json::array();
    for (const auto& b : band.points) c.push_back(b.*member);
    return c;
  };
  using B = fit::BandPoint;
  j["frequency_Hz"] = column(&B::frequency_Hz);
  j["storage_MPa"] = column(&B::storage);
  j["storage_low_MPa"] = column(&B::storage_low);
  j["storage_high_MPa"] = column(&B::storage_high);
  j["loss_MPa"] = column(&B::loss);
  j["loss_low_MPa"] = column(&B::loss_low);
  j["loss_high_MPa"] = column(&B::loss_high);
  j["tan_delta"] = column(&B::tan_delta);
  j["tan_delta_low"] = column(&B::tan_delta_low);
  j["tan_delta_high"] = column(&B::tan_delta_high);
  return j;
}

// fit.covariance (docs/formats.md §3): the free parameters' covariance in the fitted coordinates.
nlohmann::json covariance_json(const fit::FitResult& r) {
  nlohmann::json names = nlohmann::json::array(), coordinates = nlohmann::json::array();
  for (std::size_t k = 0; k < r.covariance.index.size(); ++k) {
    names.push_back(r.parameters[r.covariance.index[k]].name);
    coordinates.push_back(r.covariance.log[k] ? "ln" : "value");
  }
  return {{"parameters", names}, {"coordinates", coordinates}, {"matrix", r.covariance.matrix}};
}

}  // namespace

FeCost fe_cost(const model::Model& model, const std::vector<double>& values) {
  FeCost cost;
  model::MaxwellSeries s;
  if (!exact_maxwell_series(model, values, &s) || model.native_mode() == model::TestMode::bulk) return cost;
  for (double m : s.moduli) cost.terms += m > 0.0;
  const bool bulk_relaxes =
      elastic_constants(model.native_mode(), s.glassy(), model.bulk_modulus(values.data()), kDefaultPoissonRatio)
          .bulk_relaxes;
  cost.state_variables = cost.terms * (bulk_relaxes ? 12 : 6);
  return cost;
}

nlohmann::json admissible_to_json(const fit::AdmissibleWindow& w) {
  nlohmann::json j = {{"tau_min_s", w.tau_min_s}, {"tau_max_s", w.tau_max_s},
                      {"modulus_max_MPa", w.modulus_max_MPa}, {"relaxed_min_MPa", w.relaxed_min_MPa}};
  if (w.glassy_modulus_max_MPa > 0.0) j["glassy_modulus_max_MPa"] = w.glassy_modulus_max_MPa;
  return j;
}

Card card_from_fit(const fit::FitResult& r, const fit::FitOptions& options,
                   const data::DynamicTestTable& table, const CardProvenance& provenance) {
  using nlohmann::json;
  Card card;
  card.name = provenance.name;
  card.model_kind = r.model->kind();
  card.model_options = r.model->options();
  for (const auto& p : r.parameters)
    card.parameters.push_back({p.value, p.fixed, p.std_error, p.reason, p.ci95_low, p.ci95_high});
  const auto& m = r.metrics;
  json identifiability = {{"rank", r.identifiability.rank},
                          {"condition_number", r.identifiability.condition_number},
                          {"not_identifiable", r.identifiability.not_identifiable},
                          {"null_space_directions", r.identifiability.null_space},
                          {"correlated", json::array()}};
  for (const auto& pair : r.identifiability.correlated)
    identifiability["correlated"].push_back({pair.a, pair.b, pair.correlation});
  card.fit = {{"objective", r.objective},
              {"identifiability", identifiability},
              {"residual", fit::to_string(options.residual)},
              {"weights", {{"storage", options.storage_weight},
                           {"loss", options.loss_weight},
                           {"mean", options.mean_weight}}},
              {"backend", r.backend_used},
              {"seed", options.seed},
              {"n_points", m.n_points},
              {"n_residuals", m.n_residuals},
              {"n_free", m.n_free},
              {"rms_log10_storage", m.rms_log10_storage},
              {"rms_log10_loss", m.rms_log10_loss},
              {"mean_rel_error", m.mean_rel_error},
              {"max_rel_error", m.max_rel_error},
              {"aic", m.aic},
              {"bic", m.bic},
              {"converged", m.converged},
              {"condition_number", m.condition_number},
              {"rank", m.rank},
              {"iterations", m.iterations},
              {"messages", r.messages}};
  card.fit["quality"] = quality_json(r.quality);
  if (!r.band.points.empty()) card.fit["confidence_band"] = band_json(r.band);
  if (!r.covariance.index.empty()) card.fit["covariance"] = covariance_json(r);
  const FeCost cost = fe_cost(*r.model, r.values);
  if (cost.terms > 0)
    card.fit["fe_cost"] = {{"terms", cost.terms}, {"state_variables_per_integration_point", cost.state_variables}};
  if (r.admissible.applies) card.fit["admissible"] = admissible_to_json(r.admissible);
  const auto window = data_window_json(provenance.measured ? *provenance.measured : table, r.model.get(), r.values);
  if (!window.empty()) card.fit["data_window"] = window;
  if (provenance.record_timing) card.fit["wall_time_s"] = m.wall_time_s;
  drop_non_finite(card.fit);
  card.provenance = {{"data_files", table.source_files},
                     {"data_sha256", table.source_sha256},
                     {"fitlib_version", FITLIB_VERSION},
                     {"command", provenance.command}};
  return card;
}

}  // namespace fitlib::card
