#include "fitlib/card/data_window.hpp"

#include <algorithm>
#include <cmath>

namespace fitlib::card {
namespace {

// Values within this relative distance of a bound are inside (the card's decimal form of it).
constexpr double kBoundSlack = 1e-9;

void widen(double x, double& lo, double& hi) {
  lo = std::min(lo, x);
  hi = std::max(hi, x);
}

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

}  // namespace

nlohmann::json data_window_json(const data::DynamicTestTable& measured, const model::Model* model,
                                const std::vector<double>& p) {
  nlohmann::json w = nlohmann::json::object();
  if (has_law(model)) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& row : measured.rows) {
      const double reduced = row.condition.frequency_Hz * shift_factor(*model, p, row.condition.temperature_C);
      if (std::isfinite(reduced)) widen(reduced, lo, hi);
    }
    if (lo <= hi) w["reduced_frequency_Hz"] = {lo, hi};
  }
  double f_lo = INFINITY, f_hi = -INFINITY, T_lo = INFINITY, T_hi = -INFINITY, a_lo = INFINITY, a_hi = -INFINITY;
  for (const auto& row : measured.rows) {
    const auto& c = row.condition;
    if (std::isfinite(c.frequency_Hz)) widen(c.frequency_Hz, f_lo, f_hi);
    if (std::isfinite(c.temperature_C)) widen(c.temperature_C, T_lo, T_hi);
    if (std::isfinite(c.strain_amplitude) && c.strain_amplitude > 0.0) widen(c.strain_amplitude, a_lo, a_hi);
  }
  if (f_lo <= f_hi) w["frequency_Hz"] = {f_lo, f_hi};
  if (T_lo <= T_hi) w["temperature_C"] = {T_lo, T_hi};
  if (a_lo <= a_hi) w["strain_amplitude"] = {a_lo, a_hi};
  return w;
}

std::vector<WindowExcess> outside_data_window(const Card& card, const model::TestCondition& c) {
  std::vector<WindowExcess> out;
  const auto w = card.fit.value("data_window", nlohmann::json::object());
  if (!w.is_object()) return out;
  // `scale` divides the stored bounds: the reduced-frequency window seen at c's temperature.
  const auto check = [&](const char* quantity, const char* key, double value, double scale = 1.0) {
    const auto it = w.find(key);
    if (it == w.end() || !it->is_array() || it->size() != 2 || !std::isfinite(value)) return;
    const double lo = (*it)[0].get<double>() / scale, hi = (*it)[1].get<double>() / scale;
    const double slack = kBoundSlack * std::max(std::abs(lo), std::abs(hi));
    if (value < lo - slack || value > hi + slack) out.push_back({quantity, key, value, lo, hi});
  };
  double a_T = NAN;
  if (w.contains("reduced_frequency_Hz")) {
    const auto model = card.model();
    if (has_law(model.get())) a_T = shift_factor(*model, card.values(), c.temperature_C);
  }
  if (std::isfinite(a_T)) check("frequency_Hz", "reduced_frequency_Hz", c.frequency_Hz, a_T);
  else check("frequency_Hz", "frequency_Hz", c.frequency_Hz);
  check("temperature_C", "temperature_C", c.temperature_C);
  if (c.strain_amplitude > 0.0) check("strain_amplitude", "strain_amplitude", c.strain_amplitude);
  return out;
}

}  // namespace fitlib::card
