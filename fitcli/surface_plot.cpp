// fitcli surface fit --plot: the surface along each axis through the data (docs/surface.md
// "Figure"). Panel k draws y against axis k for each occupied combination of the other axes'
// levels (at most kMaxCurves), the measured points of that combination on it, so that a swing
// between levels or an empty cell's constraint is seen where the statistics at the points do not.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "output.hpp"
#include "plot.hpp"

namespace fitcli {
namespace {

constexpr std::size_t kMaxCurves = 12;
constexpr int kCurvePoints = 121;
const char* const kColours[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02",
                                "#a6761d", "#666666", "#1f78b4", "#e31a1c", "#33a02c", "#6a3d9a"};

// One panel: the curves along axis k and the points of each.
void axis_panel(std::ostringstream& s, const fitlib::surface::Surface& surface, const fitlib::surface::SampleSet& data,
                std::size_t k) {
  const std::size_t n = surface.axes.size();
  std::map<std::vector<int>, std::vector<Eigen::Index>> rows_of;  // the other axes' levels → data rows
  for (Eigen::Index r = 0; r < data.x.rows(); ++r) {
    std::vector<int> combo;
    for (std::size_t j = 0; j < n; ++j)
      if (j != k) combo.push_back(surface.axes[j].nearest_level(data.x(r, static_cast<Eigen::Index>(j))));
    rows_of[combo].push_back(r);
  }
  const fitlib::surface::Axis& a = surface.axes[k];
  std::ostringstream plot;
  std::size_t c = 0;
  for (const auto& [combo, rows] : rows_of) {
    if (c == kMaxCurves) break;
    std::vector<double> x(n);
    std::string label;
    for (std::size_t j = 0, m = 0; j < n; ++j) {
      if (j == k) continue;
      x[j] = surface.axes[j].levels[static_cast<std::size_t>(combo[m++])];
      label += (label.empty() ? "" : ", ") + surface.axes[j].name + " " + fitlib::core::format_number(x[j], 4);
    }
    s << "$c" << k << "_" << c << " << EOD\n";
    for (int i = 0; i < kCurvePoints; ++i) {
      x[k] = a.value_at(double(i) / (kCurvePoints - 1));
      s << exact(x[k]) << " " << exact(surface.value(x.data(), true)) << "\n";
    }
    s << "EOD\n$p" << k << "_" << c << " << EOD\n";
    for (const Eigen::Index r : rows) s << exact(data.x(r, static_cast<Eigen::Index>(k))) << " " << exact(data.y[r]) << "\n";
    s << "EOD\n";
    const std::string colour = std::string("lc rgb '") + kColours[c] + "'";
    plot << "$c" << k << "_" << c << " using 1:2 with lines " << colour << " title " << gnuplot_quoted(label)
         << " noenhanced, $p" << k << "_" << c << " using 1:2 with points pt 7 ps 0.9 " << colour << " notitle, ";
    ++c;
  }
  s << "set title " << gnuplot_quoted("along " + a.name + (rows_of.size() > kMaxCurves ? " (the first 12 level combinations)" : ""))
    << " noenhanced\nset xlabel " << gnuplot_quoted(a.name) << " noenhanced\n"
    << (a.transform == fitlib::surface::Transform::log10 ? "set logscale x\n" : "unset logscale x\n")
    << "set xrange [" << exact(a.start) << ":" << exact(a.end) << "]\n"
    << "plot " << plot.str().substr(0, plot.str().size() - 2) << "\n";
}

}  // namespace

std::string surface_plot_script(const fitlib::surface::Surface& surface, const fitlib::surface::SampleSet& data,
                                const std::string& png) {
  for (const auto& a : surface.axes)
    if (a.scattered || a.levels.empty())
      throw fitlib::core::UsageError("--plot draws the surface through the data's levels, and axis '" + a.name +
                                     "' has no levels (scattered values): evaluate it with surface eval instead");
  const std::size_t n = surface.axes.size();
  std::ostringstream s;
  s << "set terminal pngcairo size " << 560 * std::min<std::size_t>(n, 3) << "," << 600 * ((n + 2) / 3)
    << " enhanced font 'DejaVu Sans,10' linewidth 1.3\nset output '" << png << "'\n"
    << "set grid lc rgb '#dddddd'\nset format y '%g'\nset key outside bottom center horizontal font ',8'\nset ylabel "
    << gnuplot_quoted(surface.dependent_name) << " noenhanced\n"
    << (surface.dependent_transform == fitlib::surface::Transform::log10 ? "set logscale y\n" : "")
    << "set multiplot layout " << (n + 2) / 3 << "," << std::min<std::size_t>(n, 3) << " title "
    << gnuplot_quoted("surface of " + surface.dependent_name + (surface.name.empty() ? "" : " (" + surface.name + ")") +
                      ": lines the surface, points the data") << " noenhanced font ',12'\n";
  for (std::size_t k = 0; k < n; ++k) axis_panel(s, surface, data, k);
  return s.str() + "unset multiplot\n";
}

}  // namespace fitcli
