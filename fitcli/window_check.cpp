#include "window_check.hpp"

#include <algorithm>

#include "fitlib/core/error.hpp"
#include "output.hpp"

namespace fitcli {
namespace {

// "--temperature-c 300 is outside the card's data window [23, 60] degC", or for a range of values
// "--frequency-hz 1e-12 … 1e+14 reaches beyond the card's data window [0.1, 100] Hz".
std::string excess_text(const fitlib::card::WindowExcess& x, double highest) {
  const bool f = x.quantity == "frequency_Hz", T = x.quantity == "temperature_C";
  const std::string option = f ? "--frequency-hz" : T ? "--temperature-c" : "--amplitude";
  const std::string values = highest != x.value ? exact(x.value) + " … " + exact(highest) + " reaches beyond"
                                                : exact(x.value) + " is outside";
  return option + " " + values + " the card's data window [" + exact(x.low) + ", " + exact(x.high) + "]" +
         (f ? " Hz" : T ? " degC" : "") +
         (x.key != x.quantity ? " (its measured frequencies shifted to this temperature by the card's law)" : "");
}

}  // namespace

WindowCheck::WindowCheck(std::string command, std::string card_path, const fitlib::card::Card& card,
                         const std::vector<double>& temperatures_C, bool allow_extrapolation)
    : command_(std::move(command)), card_path_(std::move(card_path)), allow_(allow_extrapolation), window_(card) {
  for (double T : temperatures_C) fitlib::card::require_material_at(card, card_path_, T, card_path_, "--temperature-c");
  if (const std::string q = fitlib::card::fit_quality_warning(card); !q.empty()) warning(q + " (" + card_path_ + ")");
}

bool WindowCheck::beyond(const fitlib::model::TestCondition& c) {
  if (window_.reads_unknown_amplitude(c.strain_amplitude))
    unknown_amplitude_ = std::max(unknown_amplitude_, c.strain_amplitude);
  const auto excess = window_.outside(c);
  if (excess.empty()) return false;
  if (!allow_)
    throw fitlib::core::InputError(command_ + ": " + excess_text(excess.front(), excess.front().value) +
                                       "; pass --allow-extrapolation to evaluate there anyway",
                                   card_path_, 0, 0, "fit.data_window." + excess.front().key);
  for (const auto& x : excess) {
    const auto [it, added] = seen_.emplace(x.quantity, Seen{x, x.value});
    if (added) continue;
    it->second.first.value = std::min(it->second.first.value, x.value);
    it->second.highest = std::max(it->second.highest, x.value);
  }
  return true;
}

WindowCheck::~WindowCheck() {
  for (const auto& [quantity, s] : seen_)
    warning("extrapolating: " + excess_text(s.first, s.highest) + " (" + card_path_ + ")");
  if (unknown_amplitude_ > 0.0)
    warning(std::string("the card ") + window_.unknown_amplitude_clause() + ", and --amplitude " +
            exact(unknown_amplitude_) + " is beyond 1 %: " + window_.unknown_amplitude_consequence() + " (" + card_path_ + ")");
}

}  // namespace fitcli
