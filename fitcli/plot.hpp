#pragma once
// The figure of fitcli plot (data against a card, PNG via gnuplot), also written by fit --plot
// and eval --plot.
#include <string>
#include <vector>

#include "fitlib/card/card.hpp"

namespace fitcli {

// `data`: readable paths (inputs.hpp input_paths); `format`: native | pyvisco | eplexor;
// `title`: empty = the card's name. The PNG is written to a temporary beside `out` and renamed.
void plot_card(const fitlib::card::Card& card, const std::vector<std::string>& data, const std::string& format,
               const std::string& title, const std::string& out);

}  // namespace fitcli
