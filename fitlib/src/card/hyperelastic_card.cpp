// Quasi-static rows → hyperelastic card (card/hyperelastic.hpp).
#include <cmath>

#include "fitlib/card/hyperelastic.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib::card {

nlohmann::json figures_json(const std::vector<fit::ModeFigure>& figures) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& f : figures) {
    nlohmann::json j = {{"mode", model::to_string(f.mode)}, {"count", f.count},
                        {"rms_rel_error", f.rms_rel_error}, {"mean_rel_error", f.mean_rel_error},
                        {"max_rel_error", f.max_rel_error}, {"max_at", f.max_at},
                        {model::abscissa_name(f.mode) + std::string("_range"), {f.abscissa_min, f.abscissa_max}}};
    if (!std::isfinite(f.max_rel_error)) j.erase("max_rel_error"), j.erase("rms_rel_error"), j.erase("mean_rel_error");
    out.push_back(j);
  }
  return out;
}

namespace {

nlohmann::json stability_json(const std::vector<fit::StabilityFinding>& findings) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& s : findings) {
    nlohmann::json j = {{"mode", model::to_string(s.mode)}, {"direction", s.tension ? "tension" : "compression"},
                        {"checked_to_stretch", s.checked_to}, {"stable", s.unstable_from <= 0.0}};
    if (s.unstable_from > 0.0) j[s.locking ? "locked_from_stretch" : "unstable_from_stretch"] = s.unstable_from;
    out.push_back(j);
  }
  return out;
}

}  // namespace

HyperelasticCardResult fit_hyperelastic_card(const data::QuasiStaticTable& table, const HyperelasticCardOptions& o) {
  const model::ModelPtr m = model::make_model(o.model, o.model_options);
  if (!m->hyperelastic())
    throw core::UsageError("model '" + o.model + "' is not hyperelastic: quasi-static tables need one of " + [] {
      std::string s;
      for (const auto& k : model::hyperelastic_kinds()) s += (s.empty() ? "" : ", ") + k;
      return s;
    }());
  HyperelasticCardResult r{Card{}, fit::fit_hyperelastic(table, m, o.fit)};
  Card& card = r.card;
  card.name = o.name.empty() ? o.model + "-fit" : o.name;
  card.model_kind = m->kind();
  card.model_options = m->options();
  const auto& f = r.result;
  for (std::size_t k = 0; k < f.values.size(); ++k)
    card.parameters.push_back({f.values[k], false, f.std_error[k], f.std_error_reason[k], f.ci95_low[k], f.ci95_high[k]});
  nlohmann::json weights = nlohmann::json::object();
  for (const auto& [mode, w] : o.fit.mode_weights) weights[model::to_string(mode)] = w;
  card.fit = {{"objective", "quasi-static nominal stress"},
              {"residual", fit::to_string(o.fit.residual)},
              {"mode_weights", weights},
              {"backend", "ceres"},
              {"seed", o.fit.seed},
              {"starts", f.starts},
              {"n_points", f.n_points},
              {"n_free", f.n_free},
              {"cost", f.cost},
              {"converged", f.converged},
              {"iterations", f.iterations},
              {"initial_shear_modulus_MPa", m->hyperelastic()->initial_shear_modulus(f.values.data())},
              {"messages", f.messages},
              {"quality", {{"acceptable", f.acceptable()}, {"warnings", f.warnings}, {"figures", figures_json(f.figures)}}},
              {"stability", stability_json(f.stability)}};
  card.provenance = {{"data_files", table.source_files},
                     {"data_sha256", table.source_sha256},
                     {"fitlib_version", FITLIB_VERSION},
                     {"command", o.command}};
  return r;
}

Card visco_hyperelastic_card(const Card& base, const Card& prony, const std::string& name) {
  if (!base.model()->hyperelastic()) throw core::UsageError("the base card (model " + base.model_kind + ") is not hyperelastic");
  model::MaxwellSeries s;
  const auto pv = prony.values();
  if (!prony.model()->maxwell_series(pv.data(), &s) || prony.model()->native_mode() != model::TestMode::shear)
    throw core::UsageError("the Prony card (model " + prony.model_kind + ") is no exact shear Maxwell series");
  Card c;
  c.name = name;
  c.model_kind = "visco-hyperelastic";
  c.model_options = {{"base", base.model_kind}, {"base_options", base.model_options}, {"terms", s.moduli.size()}};
  c.parameters = base.parameters;
  for (double G : s.moduli) {
    ParameterEstimate e;
    e.value = G / s.glassy();
    e.std_error_reason = "relative modulus of the Prony card";
    c.parameters.push_back(e);
  }
  for (double tau : s.times_s) {
    ParameterEstimate e;
    e.value = tau;
    e.std_error_reason = "time of the Prony card";
    c.parameters.push_back(e);
  }
  c.model();  // checks the combination (Σ g_i < 1, the base's options)
  c.fit = {{"base", base.fit}, {"prony", prony.fit},
           {"quality", {{"warnings", nlohmann::json::array()}}}};
  for (const auto& [label, part] : {std::pair{"base card: ", &base}, std::pair{"prony card: ", &prony}}) {
    const auto q = part->fit.find("quality");
    if (q == part->fit.end() || !q->contains("warnings") || !(*q)["warnings"].is_array()) continue;
    for (const auto& w : (*q)["warnings"])
      if (w.is_string()) c.fit["quality"]["warnings"].push_back(label + w.get<std::string>());
  }
  c.fit["quality"]["acceptable"] = c.fit["quality"]["warnings"].empty();
  c.provenance = {{"base", base.provenance}, {"prony", prony.provenance}, {"fitlib_version", FITLIB_VERSION}};
  return c;
}

}  // namespace fitlib::card
