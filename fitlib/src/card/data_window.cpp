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

}  // namespace

nlohmann::json data_window_json(const data::DynamicTestTable& measured) {
  double f_lo = INFINITY, f_hi = -INFINITY, T_lo = INFINITY, T_hi = -INFINITY, a_lo = INFINITY, a_hi = -INFINITY;
  for (const auto& row : measured.rows) {
    const auto& c = row.condition;
    if (std::isfinite(c.frequency_Hz)) widen(c.frequency_Hz, f_lo, f_hi);
    if (std::isfinite(c.temperature_C)) widen(c.temperature_C, T_lo, T_hi);
    if (std::isfinite(c.strain_amplitude) && c.strain_amplitude > 0.0) widen(c.strain_amplitude, a_lo, a_hi);
  }
  nlohmann::json w = nlohmann::json::object();
  if (f_lo <= f_hi) w["frequency_Hz"] = {f_lo, f_hi};
  if (T_lo <= T_hi) w["temperature_C"] = {T_lo, T_hi};
  if (a_lo <= a_hi) w["strain_amplitude"] = {a_lo, a_hi};
  return w;
}

std::vector<WindowExcess> outside_data_window(const Card& card, const model::TestCondition& c) {
  std::vector<WindowExcess> out;
  const auto w = card.fit.value("data_window", nlohmann::json::object());
  if (!w.is_object()) return out;
  const auto check = [&](const char* quantity, double value) {
    const auto it = w.find(quantity);
    if (it == w.end() || !it->is_array() || it->size() != 2 || !std::isfinite(value)) return;
    const double lo = (*it)[0].get<double>(), hi = (*it)[1].get<double>();
    const double slack = kBoundSlack * std::max(std::abs(lo), std::abs(hi));
    if (value < lo - slack || value > hi + slack) out.push_back({quantity, value, lo, hi});
  };
  check("frequency_Hz", c.frequency_Hz);
  check("temperature_C", c.temperature_C);
  if (c.strain_amplitude > 0.0) check("strain_amplitude", c.strain_amplitude);
  return out;
}

}  // namespace fitlib::card
