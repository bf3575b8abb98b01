#pragma once
// The data window of a card: the box of test conditions (frequency, temperature, strain
// amplitude) of the measured rows it was fitted to, stored as "fit.data_window"
// (docs/formats.md §3). fitcli eval refuses conditions outside it unless told to extrapolate
// (docs/decisions.md, "eval: the data window").
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fitlib/card/card.hpp"
#include "fitlib/data/table.hpp"

namespace fitlib::card {

// {"frequency_Hz": [lo, hi], "temperature_C": [lo, hi], "strain_amplitude": [lo, hi]}, each
// present only when the rows give it (finite temperatures, amplitudes above 0).
nlohmann::json data_window_json(const data::DynamicTestTable& measured);

// One condition outside the window: which quantity, the value and the window's bounds.
struct WindowExcess {
  std::string quantity;  // "frequency_Hz" | "temperature_C" | "strain_amplitude"
  double value = 0.0, low = 0.0, high = 0.0;
};

// The quantities of `c` beyond the card's window (none when the card stores no window).
std::vector<WindowExcess> outside_data_window(const Card& card, const model::TestCondition& c);

}  // namespace fitlib::card
