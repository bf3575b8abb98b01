#pragma once
// The data window of a card: the box of test conditions (frequency, temperature, strain
// amplitude) of the measured rows it was fitted to, stored as "fit.data_window"
// (docs/formats.md §3). fitcli eval refuses conditions outside it unless told to extrapolate
// (docs/decisions.md, "eval: the data window").
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fitlib/card/card.hpp"
#include "fitlib/data/table.hpp"

namespace fitlib::card {

// {"frequency_Hz": [lo, hi], "temperature_C": [lo, hi], "strain_amplitude": [lo, hi]}, each
// present only when the rows give it (finite temperatures, amplitudes above 0); with a model with
// damage and amplitudes, "damage_driver": the largest of each driver the rows' tests reach. With a model
// that carries a temperature law (and its parameters p), also "reduced_frequency_Hz": the
// rows' f·a_T(T) — time–temperature superposition makes a frequency measured at another
// temperature data at the reference, so eval checks f·a_T against it instead of f.
nlohmann::json data_window_json(const data::DynamicTestTable& measured, const model::Model* model = nullptr,
                                const std::vector<double>& p = {});

// One condition outside the window: which quantity, the value and the window's bounds.
struct WindowExcess {
  std::string quantity;  // "frequency_Hz" | "temperature_C" | "strain_amplitude"
  std::string key;       // the window's key: the quantity, or "reduced_frequency_Hz"
  double value = 0.0, low = 0.0, high = 0.0;
};

// A card's window, read once (and its model built once when the window is in reduced frequency)
// for evaluating many conditions.
class DataWindow {
 public:
  explicit DataWindow(const Card& card);
  // The quantities of `c` beyond the window (none when the card stores no window); with a
  // reduced-frequency window the frequency bounds are those at c's temperature (f_lo/a_T, f_hi/a_T)
  // when that temperature is within the measured ones, else the measured frequencies' box.
  std::vector<WindowExcess> outside(const model::TestCondition& c) const;
  // True when the rows gave no strain amplitude (a small-amplitude test, or a card written by
  // hand: no amplitude is outside, the card's strain range is not known) and `strain_amplitude`
  // lies beyond kSmallAmplitudeEnd — the caller says so (unknown_amplitude_clause) and goes on.
  bool reads_unknown_amplitude(double strain_amplitude) const;
  // What such a reading means: a card whose model does not depend on the amplitude "holds no strain
  // amplitude (… a small-amplitude test)" and answers alike at every amplitude; a damage model's
  // card (model::Model::amplitude_dependent, e.g. written by hand from the thesis's parameters)
  // softens there by its law, but no test behind it says how far that law holds.
  const char* unknown_amplitude_clause() const;
  const char* unknown_amplitude_consequence() const;
  bool amplitude_dependent() const;
  // The largest damage driver of each of the model's (Model::damage_drivers) that its rows reached
  // ("damage_driver"); empty for a model without damage, or a card written before it was stored.
  const std::vector<double>& damage_drivers() const { return damage_driver_; }
  // The strain amplitudes of its rows ("strain_amplitude": [lo, hi]); none when they gave none.
  const std::optional<std::pair<double, double>>& strain_amplitude_range() const { return amplitude_; }

 private:
  std::optional<std::pair<double, double>> frequency_, reduced_, temperature_, amplitude_;
  std::vector<double> damage_driver_;
  model::ModelPtr model_;  // the card's model (a_T when reduced_ is set, its amplitude dependence)
  std::vector<double> values_;
};

// A card that knows no strain amplitude is named when read beyond this one (the scene's segment
// levels; fitcli eval, synth, material-point, surface grid): it answers alike at every amplitude,
// where a filled rubber softens (docs/decisions.md "Life: a card without strain amplitudes driven
// beyond 1 % is a warning"); DataWindow::unknown_amplitude_clause is the warnings' common clause.
constexpr double kSmallAmplitudeEnd = 0.01;

// DataWindow(card).outside(c), for one condition.
std::vector<WindowExcess> outside_data_window(const Card& card, const model::TestCondition& c);

}  // namespace fitlib::card
