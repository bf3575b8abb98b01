#pragma once
// Conditions beyond a card's data window (card/data_window.hpp): refused, or with
// --allow-extrapolation evaluated and said once per quantity (eval, synth, material-point).
#include <map>
#include <string>
#include <vector>

#include "fitlib/card/card.hpp"
#include "fitlib/card/data_window.hpp"
#include "fitlib/model/model.hpp"

namespace fitcli {

class WindowCheck {
 public:
  // A temperature where the card's law describes no material is refused first, even with
  // --allow-extrapolation. `command` prefixes the error ("eval").
  WindowCheck(std::string command, std::string card_path, const fitlib::card::Card& card,
              const std::vector<double>& temperatures_C, bool allow_extrapolation);
  WindowCheck(const WindowCheck&) = delete;
  WindowCheck& operator=(const WindowCheck&) = delete;
  // Each quantity's range beyond the window, one warning at the end; and one when a card that
  // knows no strain amplitude was read beyond card::kSmallAmplitudeEnd.
  ~WindowCheck();

  // True when `c` lies beyond the window (and extrapolation is allowed); InputError naming the
  // window's key when it is not.
  bool beyond(const fitlib::model::TestCondition& c);

 private:
  struct Seen {
    fitlib::card::WindowExcess first;  // its value the lowest seen
    double highest;
  };
  std::string command_, card_path_;
  bool allow_;
  const fitlib::card::DataWindow window_;
  std::map<std::string, Seen> seen_;
  double unknown_amplitude_ = 0.0;  // the largest amplitude above 1 % on a card that knows none
};

}  // namespace fitcli
