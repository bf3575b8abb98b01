// The figures of scene runs. fitcli life --plot (docs/fatigue.md §8 "Figure"): top, the load cycle
// the segment was driven by (belt force and neutral-layer curvature against time, the pulleys'
// contact arcs shaded); below, one panel per mode: the effective stress σ_e on the crack plane at
// the design point over the last cycle, with the significant peaks that enter Σ(σ_e/σ0)ⁿ.
// fitcli belt --plot (docs/belt.md "Figure"): the same load-cycle panel, then the side pressure
// with the friction used, and the sliding angle with the flank's sliding speed.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "fitlib/core/error.hpp"
#include "fitlib/fatigue/card.hpp"
#include "output.hpp"
#include "plot.hpp"

namespace fitcli {
namespace {

// Three significant digits, or fewer for a life read beyond its cards' tests (ModeLife::significant_digits).
std::string cycles_text(double n, int digits = 3) {
  if (!std::isfinite(n)) return "unbounded";
  char b[48];
  std::snprintf(b, sizeof b, "%.*g cycles", std::min(digits, 3), n);
  return b;
}

// One mode's panel: σ_e(t) in ms within the cycle, the peaks as points. The last cycle starts
// mid-span (Report I's loading), so times are taken modulo the cycle and sorted: the cycle is
// periodic, its end joins its start.
void mode_panel(std::ostringstream& s, const fitlib::fatigue::ModeLife& m, double cycle_s, int k) {
  auto in_cycle_ms = [cycle_s](double t) { return 1e3 * (t - cycle_s * std::floor(t / cycle_s)); };
  std::vector<std::pair<double, double>> history;
  for (std::size_t i = 0; i < m.t_s.size(); ++i) history.emplace_back(in_cycle_ms(m.t_s[i]), m.effective_stress_MPa[i]);
  std::sort(history.begin(), history.end());
  if (!history.empty()) history.emplace_back(history.front().first + 1e3 * cycle_s, history.front().second);
  s << "$e" << k << " << EOD\n";
  for (const auto& [t, stress] : history) s << exact(t) << " " << exact(stress) << "\n";
  s << "EOD\n$p" << k << " << EOD\n";
  for (const auto& p : m.peaks) s << exact(in_cycle_ms(p.t_s)) << " " << exact(p.stress_MPa) << "\n";
  s << "EOD\n";
}

// The terminal, the load cycle's samples ($load: t ms, F, K, p, friction used, γ deg, sliding speed)
// and the contact arcs, shaded in every panel.
void load_cycle_data(std::ostringstream& s, const fitlib::belt::LoadCycle& cycle, int panels, const std::string& png) {
  s << "set terminal pngcairo size 1200," << 260 + 280 * panels
    << " enhanced font 'DejaVu Sans,11' linewidth 1.3\nset output '" << png << "'\n"
    << "set grid lc rgb '#dddddd'\nset key inside top left box opaque font ',9'\nset lmargin 10\nset rmargin 11\n"
    << "set offsets 0, 0, graph 0.08, graph 0.04\nset xrange [0:" << exact(1e3 * cycle.cycle_time_s) << "]\n$load << EOD\n";
  for (const auto& x : cycle.samples)
    s << exact(1e3 * x.t_s) << " " << exact(x.F_N) << " " << exact(x.K_1_mm) << " " << exact(x.p_MPa) << " "
      << exact(x.friction_used) << " " << exact(x.gamma_rad * 57.29577951308232) << " " << exact(x.slide_mm_s) << "\n";
  s << "EOD\n";
  const double ms_per_mm = 1e3 * cycle.cycle_time_s / cycle.cycle_length_mm;
  int object = 1;
  for (const auto& p : cycle.pulleys)
    s << "set object " << object++ << " rect from " << exact(ms_per_mm * p.s_Cin_mm) << ", graph 0 to "
      << exact(ms_per_mm * p.s_Cout_mm) << ", graph 1 fc rgb '#eeeeee' fs solid noborder behind\n";
}

// The multiplot's title and its first panel: F and K against time.
void load_cycle_panel(std::ostringstream& s, const fitlib::belt::LoadCycle& cycle, int panels, const std::string& title) {
  double K_low = 0.0, K_high = 0.0;
  for (const auto& x : cycle.samples) K_low = std::min(K_low, x.K_1_mm), K_high = std::max(K_high, x.K_1_mm);
  s << "set multiplot layout " << panels << ",1 title " << gnuplot_quoted(title + "; grey: pulley contact")
    << " noenhanced font ',11'\nset ylabel 'belt force F [N]'\nset y2label 'curvature K [1/mm]'\nset ytics nomirror\n"
    << "set y2tics\nset y2range [" << exact(K_low - 0.05 * (K_high - K_low)) << ":"
    << exact(K_high + 0.1 * (K_high - K_low) + 1e-12) << "]\nplot $load using 1:2 with lines lc rgb '#2c7bb6' title 'F', $load using 1:3 axes x1y2 with lines "
       "lc rgb '#d7191c' title 'K'\nset y2range [*:*]\n";
}

std::string scene_title(const fitlib::scene::Scene& scene) {
  return scene.name + " (" + fitlib::core::short_number(scene.temperature_C) + " °C)";
}

}  // namespace

std::string belt_plot_script(const fitlib::scene::Scene& scene, const fitlib::belt::LoadCycle& cycle, const std::string& png) {
  std::ostringstream s;
  load_cycle_data(s, cycle, 3, png);
  load_cycle_panel(s, cycle, 3, scene_title(scene) + ": the load cycle of a belt element");
  double friction_top = 0.0;  // (the y offsets do not apply to y2: the full-sliding plateau would sit on the border)
  for (const auto& x : cycle.samples) friction_top = std::max(friction_top, x.friction_used);
  s << "set ylabel 'side pressure p [MPa]'\nset y2label 'friction used μ·u [-]'\nset yrange [0:*]\nset y2range [0:"
    << exact(1.15 * friction_top + 1e-12) << "]\n"
       "plot $load using 1:4 with lines lc rgb '#2c7bb6' title 'p', $load using 1:5 axes x1y2 with lines lc rgb '#1a9641' title 'μ·u'\n"
       "set xlabel 'time in the load cycle [ms]'\nset ylabel 'sliding angle γ [deg]'\nset y2label 'sliding speed [mm/s]'\n"
       "set yrange [*:*]\nset y2range [*:*]\nplot $load using 1:6 with lines lc rgb '#2c7bb6' title 'γ', $load using 1:7 axes x1y2 "
       "with lines lc rgb '#d7191c' title 'sliding speed'\n";
  return s.str() + "unset multiplot\n";
}

std::string life_plot_script(const fitlib::scene::Scene& scene, const fitlib::scene::SceneResult& r,
                             const std::string& png) {
  const auto& report = r.life->report;
  const fitlib::belt::LoadCycle& cycle = *r.cycle;
  const int panels = 1 + static_cast<int>(report.modes.size());
  std::ostringstream s;
  load_cycle_data(s, cycle, panels, png);
  for (std::size_t k = 0; k < report.modes.size(); ++k) mode_panel(s, report.modes[k], cycle.cycle_time_s, static_cast<int>(k));
  int digits = 3;
  for (const auto& m : report.modes)
    if (report.governing == fitlib::fatigue::to_string(m.mode)) digits = m.significant_digits;
  const std::string governing = report.governing == "none" ? "no significant peak"
                                                            : report.governing + ", " + cycles_text(report.life_cycles, digits);
  // The level in the title: an elastic and a complete figure of one drive are read side by side.
  load_cycle_panel(s, cycle, panels, scene_title(scene) + ", " + fitlib::core::to_string(r.life->plan.fidelity) + " level: governing " + governing);
  s << "unset y2tics\nunset y2label\nset ytics mirror\nunset key\nset yrange [0:*]\n";
  for (std::size_t k = 0; k < report.modes.size(); ++k) {
    const auto& m = report.modes[k];
    if (k + 1 == report.modes.size()) s << "set xlabel 'time in the load cycle [ms]'\n";
    s << "set title " << gnuplot_quoted(std::string(fitlib::fatigue::to_string(m.mode)) + " at " + m.design_point +
                                         ": " + cycles_text(m.life_cycles, m.significant_digits) + " (red: the peaks in the sum)")
      << " noenhanced\nset ylabel 'σ_e [MPa]'\nplot $e" << k << " using 1:2 with lines lc rgb 'black', $p" << k
      << " using 1:2 with points pt 7 ps 1.1 lc rgb '#d7191c'\n";
  }
  return s.str() + "unset multiplot\n";
}

}  // namespace fitcli
