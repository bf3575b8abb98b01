#include "fitlib/card/data_window.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace fitlib::card {
namespace {

// Values within this relative distance of a bound are inside (the card's decimal form of it).
constexpr double kBoundSlack = 1e-9;

// [lo, hi] of the values seen; empty until one is.
struct Range {
  double lo = INFINITY, hi = -INFINITY;
  void widen(double x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  bool empty() const { return !(lo <= hi); }
  nlohmann::json json() const { return {lo, hi}; }
};

// a_T of the model's law at T (1 at the reference or without a law); NaN where the law has none
// (beyond a WLF pole).
double shift_factor(const model::Model& model, const std::vector<double>& p, double temperature_C) {
  if (model.temperature_law_info().law == model::ShiftLaw::none || !std::isfinite(temperature_C)) return 1.0;
  const double a_T = model.temperature_factors(p.data(), temperature_C).shift_factor;
  return std::isfinite(a_T) && a_T > 0.0 ? a_T : NAN;
}

bool has_law(const model::Model* model) {
  return model && model->temperature_law_info().law != model::ShiftLaw::none;
}

// The stored [lo, hi] of `key`, when the window holds two numbers there.
std::optional<std::pair<double, double>> bounds(const nlohmann::json& w, const char* key) {
  const auto it = w.find(key);
  if (it == w.end() || !it->is_array() || it->size() != 2) return std::nullopt;
  return std::make_pair((*it)[0].get<double>(), (*it)[1].get<double>());
}

}  // namespace

nlohmann::json data_window_json(const data::DynamicTestTable& measured, const model::Model* model,
                                const std::vector<double>& p) {
  const bool law = has_law(model);
  Range reduced, frequency, temperature, amplitude;
  std::vector<double> drivers;  // the largest damage driver each of the model's reached
  for (const auto& row : measured.rows) {
    const auto& c = row.condition;
    if (model && p.size() == model->parameters().size()) {
      const std::vector<double> d = model->damage_drivers(p.data(), c);
      drivers.resize(std::max(drivers.size(), d.size()), 0.0);
      for (std::size_t j = 0; j < d.size(); ++j) drivers[j] = std::max(drivers[j], d[j]);
    }
    if (law) {
      const double f_reduced = c.frequency_Hz * shift_factor(*model, p, c.temperature_C);
      if (std::isfinite(f_reduced)) reduced.widen(f_reduced);
    }
    if (std::isfinite(c.frequency_Hz)) frequency.widen(c.frequency_Hz);
    if (std::isfinite(c.temperature_C)) temperature.widen(c.temperature_C);
    if (std::isfinite(c.strain_amplitude) && c.strain_amplitude > 0.0) amplitude.widen(c.strain_amplitude);
  }
  nlohmann::json w = nlohmann::json::object();
  if (!reduced.empty()) w["reduced_frequency_Hz"] = reduced.json();
  if (!frequency.empty()) w["frequency_Hz"] = frequency.json();
  if (!temperature.empty()) w["temperature_C"] = temperature.json();
  if (!amplitude.empty()) w["strain_amplitude"] = amplitude.json();
  if (!amplitude.empty() && !drivers.empty()) w["damage_driver"] = drivers;
  return w;
}

DataWindow::DataWindow(const Card& card) : model_(card.model()) {
  const auto w = card.fit.value("data_window", nlohmann::json::object());
  if (!w.is_object()) return;
  frequency_ = bounds(w, "frequency_Hz");
  temperature_ = bounds(w, "temperature_C");
  amplitude_ = bounds(w, "strain_amplitude");
  if (const auto d = w.find("damage_driver"); d != w.end() && d->is_array())  // checked by card_from_json
    damage_driver_ = d->get<std::vector<double>>();
  if ((reduced_ = bounds(w, "reduced_frequency_Hz"))) {
    values_ = card.values();
    if (!has_law(model_.get())) reduced_.reset();
  }
}

std::vector<WindowExcess> DataWindow::outside(const model::TestCondition& c) const {
  std::vector<WindowExcess> out;
  // `scale` divides the stored bounds: the reduced-frequency window seen at c's temperature.
  const auto check = [&](const char* quantity, const char* key, const std::optional<std::pair<double, double>>& b,
                         double value, double scale = 1.0) {
    if (!b || !std::isfinite(value)) return;
    const double lo = b->first / scale, hi = b->second / scale;
    // Slack relative to each bound: one scaled by the larger bound would swallow a low bound
    // many decades below the high one (a reduced-frequency window spans 10+ decades).
    if (value < lo - kBoundSlack * std::abs(lo) || value > hi + kBoundSlack * std::abs(hi))
      out.push_back({quantity, key, value, lo, hi});
  };
  // The reduced window holds within the measured temperatures; beyond them the law's a_T is an
  // extrapolation itself: the temperature is named and the frequency checked against its box.
  const bool measured_T = !temperature_ || !std::isfinite(c.temperature_C) ||
                          (c.temperature_C >= temperature_->first && c.temperature_C <= temperature_->second);
  const double a_T = reduced_ && measured_T ? shift_factor(*model_, values_, c.temperature_C) : NAN;
  if (std::isfinite(a_T)) check("frequency_Hz", "reduced_frequency_Hz", reduced_, c.frequency_Hz, a_T);
  else check("frequency_Hz", "frequency_Hz", frequency_, c.frequency_Hz);
  check("temperature_C", "temperature_C", temperature_, c.temperature_C);
  if (c.strain_amplitude > 0.0) check("strain_amplitude", "strain_amplitude", amplitude_, c.strain_amplitude);
  return out;
}

bool DataWindow::reads_unknown_amplitude(double strain_amplitude) const {
  return !amplitude_ && strain_amplitude > kSmallAmplitudeEnd;
}

bool DataWindow::amplitude_dependent() const { return model_->amplitude_dependent(); }

const char* DataWindow::unknown_amplitude_clause() const {
  return amplitude_dependent() ? "holds no strain amplitude window (fit.data_window.strain_amplitude: a card written "
                                 "by hand, or fitted without amplitudes)"
                               : "holds no strain amplitude (fit.data_window.strain_amplitude: a small-amplitude test)";
}

const char* DataWindow::unknown_amplitude_consequence() const {
  return amplitude_dependent() ? "its damage law softens it there, but no test behind the card says how far that law holds"
                              : "such a card answers alike at every amplitude, where a filled rubber softens (the "
                                "thesis's cushion rubber, datasets/materials/material-2.csv, keeps 63-69 % of its "
                                "storage modulus from 0.5 % to 1.5 % amplitude)";
}

std::vector<WindowExcess> outside_data_window(const Card& card, const model::TestCondition& c) {
  return DataWindow(card).outside(c);
}

}  // namespace fitlib::card
