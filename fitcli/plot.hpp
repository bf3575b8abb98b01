#pragma once
// The figure of fitcli plot (data against a card, PNG via gnuplot), also written by fit --plot
// and eval --plot; write_png, the gnuplot runner every figure goes through.
#include <functional>
#include <stdexcept>
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

// A figure gnuplot cannot draw: exit 5 (README "Exit codes", docs/decisions.md "fitcli: a figure
// gnuplot cannot draw is exit 5"). gnuplot missing from PATH is found by claim_png, before any
// work (nothing written); gnuplot failing while it draws comes after the run's other outputs,
// which stand (draw_figure).
class FigureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
constexpr int kFigureNotDrawn = 5;

// Declares the PNG output of `option` before the work: UsageError for `-` (a figure cannot go to
// stdout) or a quote in the name, InputError for a path that cannot be written, FigureError when
// no gnuplot is on PATH. A PNG whose folder is `folder_made_later` (the command's --out-dir, made
// by the run) is not checked for its folder.
void claim_png(const std::string& option, const std::string& path, const std::string& folder_made_later = "");

// The PNG at `out` from the gnuplot script `make_script(tmp)` returns, which must write the PNG to
// `tmp` (pngcairo): gnuplot runs on it, then tmp is renamed to out. UsageError for `-` or a quote
// in the name; FigureError when gnuplot is missing or fails (no PNG written).
void write_png(const std::string& out, const std::function<std::string(const std::string& tmp)>& make_script);

// A --plot figure beside a run's other outputs: runs `draw` (which writes `png`); a FigureError
// becomes a warning naming the PNG, the run goes on to write its other outputs, and fitcli then
// exits 5 (figure_not_drawn). Returns whether the PNG was written.
bool draw_figure(const std::string& png, const std::function<void()>& draw);
bool figure_not_drawn();

}  // namespace fitcli
