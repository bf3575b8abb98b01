#include "fitlib/card/from_fit.hpp"

#include <cmath>

#include "fitlib/card/data_window.hpp"

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
  return {{"acceptable", q.acceptable()}, {"warnings", q.warnings}, {"figures", figures}};
}

}  // namespace

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
