#pragma once
// The figure of fitcli plot (data against a card, PNG via gnuplot), also written by fit --plot
// and eval --plot; write_png, the gnuplot runner every figure goes through.
#include <functional>
#include <string>
#include <vector>

#include "fitlib/card/card.hpp"
#include "fitlib/scene/results.hpp"
#include "fitlib/scene/scene.hpp"
#include "fitlib/surface/fit.hpp"

namespace fitcli {

// `data`: readable paths (inputs.hpp input_paths); `format`: native | pyvisco | eplexor;
// `title`: empty = the card's name. The PNG is written to a temporary beside `out` and renamed.
void plot_card(const fitlib::card::Card& card, const std::vector<std::string>& data, const std::string& format,
               const std::string& title, const std::string& out);

// The gnuplot script of `fitcli belt --plot` (life_plot.cpp): the load cycle's F and K, side
// pressure and friction used, sliding angle and sliding speed against time.
std::string belt_plot_script(const fitlib::scene::Scene& scene, const fitlib::belt::LoadCycle& cycle,
                             const std::string& png);
// The gnuplot script of `fitcli life --plot` (life_plot.cpp): the load cycle and each mode's σ_e
// at its design point with its peaks; `r` must hold the life and the load cycle.
std::string life_plot_script(const fitlib::scene::Scene& scene, const fitlib::scene::SceneResult& r,
                             const std::string& png);

// The gnuplot script of `fitcli surface fit --plot` (surface_plot.cpp): per axis, the surface along
// it through each occupied combination of the other axes' levels, with the data. UsageError when an
// axis has no levels (scattered).
std::string surface_plot_script(const fitlib::surface::Surface& surface, const fitlib::surface::SampleSet& data,
                                const std::string& png);

// `text` as a gnuplot single-quoted string (a quote doubled); print it with `noenhanced` so that a
// user's name keeps its _ ^ { }.
std::string gnuplot_quoted(const std::string& text);

// Declares the PNG output of `option` before the work: UsageError for `-` (a figure cannot go to
// stdout) or a quote in the name, InputError for a path that cannot be written. A PNG whose folder
// is `folder_made_later` (the command's --out-dir, made by the run) is not checked for its folder.
void claim_png(const std::string& option, const std::string& path, const std::string& folder_made_later = "");

// The PNG at `out` from the gnuplot script `make_script(tmp)` returns, which must write the PNG to
// `tmp` (pngcairo): gnuplot runs on it, then tmp is renamed to out. UsageError for `-` or a quote
// in the name; NumericalError when gnuplot is missing or fails (nothing written).
void write_png(const std::string& out, const std::function<std::string(const std::string& tmp)>& make_script);

}  // namespace fitcli
