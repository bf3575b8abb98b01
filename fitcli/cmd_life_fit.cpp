// fitcli life-fit: the life constants σ0, n, b of (6.31) per failure mode fitted to observed belt
// lives — a list of drive scenes with observed hours and failure modes (each scene run to its
// stresses) or stored peaks — written as a fatigue card with 95 % intervals (docs/fatigue.md §6).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "inputs.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/fatigue/life_fit.hpp"
#include "fitlib/scene/life_tests.hpp"
#include "output.hpp"
#include "plot.hpp"

namespace fitcli {
namespace {

struct LifeFitArgs {
  std::string observed, start, out = "life-card.json", peaks_out, plot;
  bool fix_n = false, fix_b = false, json = false;
};

// Four significant digits: the table is for reading; the card holds the exact values.
std::string sig4(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return text;
}

std::string with_interval(const fitlib::fatigue::ConstantEstimate& c) {
  if (c.fixed) return sig4(c.value) + " (held)";
  if (!c.has_interval) return sig4(c.value);
  return sig4(c.value) + " [" + sig4(c.ci95_low) + ", " + sig4(c.ci95_high) + "]";
}

std::string fit_table(const fitlib::fatigue::LifeCardFit& r) {
  std::ostringstream t;
  t << std::left << std::setw(14) << "mode" << std::setw(7) << "cases" << std::setw(9) << "runouts"
    << std::setw(28) << "sigma0_MPa [95 %]"
    << std::setw(28) << "n [95 %]" << std::setw(28) << "b_per_C [95 %]" << std::setw(11) << "rms log10"
    << "stresses\n";
  for (const auto& f : r.fits) {
    t << std::setw(14) << fitlib::fatigue::to_string(f.mode) << std::setw(7) << f.cases << std::setw(9) << f.runouts;
    if (!f.rejected.empty()) {
      t << "not fitted: the start card's constants are kept (the warning on stderr says why)\n";
      continue;
    }
    for (const auto& c : f.constants) t << std::setw(28) << with_interval(c);
    const auto& level = r.card.law(f.mode).stress_fidelity;
    t << std::setw(11) << sig4(f.rms_log10_error)
      << (level ? std::string(fitlib::core::to_string(*level)) + " level" : "not stated") << "\n";
    if (!f.note.empty()) t << "  note: " << f.note << "\n";
    if (const auto& sc = r.card.law(f.mode).scatter)  // docs/fatigue.md §9
      t << "  scatter: log-normal about the law, s " << sig4(sc->sigma_log10) << " log10 (" << sc->dof
        << " dof), with the constants' covariance, written into the card (fitcli life prints B10 and B50)\n";
  }
  return t.str();
}

// The figure (--plot): left, the S–N diagram of each fitted mode — every case at its design
// point's equivalent stress σ_eq = σ0 (Σ(σ_i/σ0)ⁿ)^(1/n) against its observed life brought to
// T_ref by 2^(b(T − T_ref)), with the fitted line N = (σ/σ0)^(−n); right, predicted against
// observed lives with the factor kScatterWarning band.
std::string life_fit_script(const std::vector<fitlib::fatigue::ObservedLife>& cases,
                            const fitlib::fatigue::LifeCardFit& fit, const std::string& title, const std::string& png) {
  using namespace fitlib::fatigue;
  using fitlib::core::short_number;
  const double T_ref = fit.card.reference_temperature_C;
  const char* colour[2] = {"#d7191c", "#2c7bb6"};
  std::ostringstream s, sn, scatter;
  double low = HUGE_VAL, high = 0.0;  // both axes of the right panel
  s << "set terminal pngcairo size 1400,620 enhanced font 'DejaVu Sans,11' linewidth 1.3\nset output '" << png
    << "'\nset grid lc rgb '#dddddd'\nset logscale xy\nset format x '10^{%L}'\nset key top right box opaque\n";
  for (const LifeFitResult& f : fit.fits) {
    if (!f.rejected.empty()) continue;
    const int m = f.mode == Mode::radial_crack ? 0 : 1;
    for (const bool runout : {false, true}) {  // $m0/$m1 the failures, $r0/$r1 the runouts
      s << (runout ? "$r" : "$m") << m << " << EOD\n";
      for (const ObservedLife& c : cases) {
        if (c.mode != f.mode || c.runout != runout) continue;
        const double lg_pred = predicted_log10_life(c, f.law, T_ref);
        const double lg_shift = f.law.b_per_C * (c.temperature_C - T_ref) * std::log10(2.0);  // N_ref = N·2^(bΔT)
        const double sigma_eq = f.law.sigma0_MPa * std::pow(10.0, -(lg_pred + lg_shift) / f.law.n);
        const double predicted = std::pow(10.0, lg_pred);
        s << exact(std::pow(10.0, std::log10(c.observed_cycles) + lg_shift)) << " " << exact(sigma_eq) << " "
          << exact(c.observed_cycles) << " " << exact(predicted) << "\n";
        low = std::min({low, c.observed_cycles, predicted}), high = std::max({high, c.observed_cycles, predicted});
      }
      s << "EOD\n";
    }
    const std::string name = to_string(f.mode), rgb = std::string("lc rgb '") + colour[m] + "'";
    // Runouts as open triangles (their lives lie beyond them), drawn only when there are some.
    auto with_columns = [&](const char* columns) {
      return f.runouts == 0 ? std::string() : "$r" + std::to_string(m) + " using " + columns +
                                                  " with points pt 8 ps 1.2 " + rgb + " title '" + name +
                                                  " runouts' noenhanced, ";
    };
    sn << "$m" << m << " using 1:2 with points pt 7 ps 0.8 " << rgb << " title '" << name << "' noenhanced, "
       << with_columns("1:2") << exact(f.law.sigma0_MPa) << "*x**(-1.0/" << exact(f.law.n) << ") with lines " << rgb
       << " title 'fit: n " << sig4(f.law.n) << ", {/Symbol s}_0 " << sig4(f.law.sigma0_MPa) << " MPa', ";
    scatter << "$m" << m << " using 3:4 with points pt 7 ps 0.8 " << rgb << " title '" << name << "' noenhanced, "
            << with_columns("3:4");
  }
  const double band = std::pow(10.0, kScatterWarning_log10);
  s << "set multiplot layout 1,2 title " << gnuplot_quoted(title) << " noenhanced font ',13'\n"
    << "set xlabel 'observed life at T_{ref} = " << short_number(T_ref) << " °C [cycles]'\nset format y '%g'\n"
    << "set ylabel 'equivalent stress at the design point [MPa]'\nplot " << sn.str().substr(0, sn.str().size() - 2)
    << "\n"
    << "set xlabel 'observed life [cycles]'\nset ylabel 'predicted life [cycles]'\nset format y '10^{%L}'\n"
    << "set size square\nset xrange [" << exact(low / 10.0) << ":" << exact(high * 10.0) << "]\nset yrange ["
    << exact(low / 10.0) << ":" << exact(high * 10.0) << "]\nset key bottom right\nplot " << scatter.str() << "x with lines lc rgb 'black' title 'predicted = observed', "
    << exact(band) << "*x with lines lc rgb 'gray50' dt 2 title 'factor " << sig4(band) << "', x/"
    << exact(band) << " with lines lc rgb 'gray50' dt 2 notitle\nunset multiplot\n";
  return s.str();
}

void run(const LifeFitArgs& a) {
  claim_output("--out", a.out, a.json);
  if (!a.peaks_out.empty()) claim_output("--peaks-out", a.peaks_out, a.json);
  if (!a.plot.empty()) claim_png("--plot", a.plot);
  const std::string text = fitlib::core::read_file(input_path(a.observed));
  const std::string source = a.observed == "-" ? "stdin" : a.observed;  // stdin: scenes from the current folder
  fitlib::scene::refuse_outputs_on_test_scenes(text, source, {{"--out", a.out}, {"--peaks-out", a.peaks_out}, {"--plot", a.plot}});
  // Progress: every test with --verbose; otherwise once the runs have taken 2 s (segment levels).
  const auto begin = std::chrono::steady_clock::now();
  fitlib::scene::LifeTestsFit tests = fitlib::scene::fit_life_tests(
      text, source, a.start, {a.fix_n, a.fix_b},
      [begin](const fitlib::scene::LifeTest& t, std::size_t k, std::size_t n) {
        const std::string line = "life test " + std::to_string(k) + "/" + std::to_string(n) + ": " + t.name;
        if (std::chrono::steady_clock::now() - begin > std::chrono::seconds(2)) note(line);
        else detail(line + " (" + t.scene_path + ")");
      });
  const auto& cases = tests.cases;
  fitlib::fatigue::LifeCardFit& fit = tests.fit;
  fit.card.provenance["command"] = with_stdin_named(command_line());
  if (!a.peaks_out.empty()) emit(a.peaks_out, fitlib::fatigue::observed_lives_csv(cases));
  emit_with(a.out, [&](const std::string& path) { fitlib::fatigue::save_card(path, fit.card); });
  if (!a.plot.empty() && !fit.fits.empty())
    draw_figure(a.plot, [&] {
      write_png(a.plot, [&](const std::string& tmp) { return life_fit_script(cases, fit, fit.card.name, tmp); });
    });
  if (a.json) {
    nlohmann::json j = fitlib::fatigue::card_to_json(fit.card);
    j["warnings"] = fit.warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  summary() << fit_table(fit);
  for (const std::string& w : fit.warnings) warning(w);  // stderr, as every command's (--quiet hides them)
  if (a.out != "-") summary() << "card written to " << a.out << "\n";
}

}  // namespace

void register_life_fit(CLI::App& app) {
  auto* cmd = app.add_subcommand("life-fit", "Fit the life constants (sigma0, n, b per failure mode) to observed belt "
                                             "lives and write a fatigue card with 95 % intervals");
  auto a = std::make_shared<LifeFitArgs>();
  cmd->add_option("--observed", a->observed,
                  "CSV of life tests (scene, failure_mode, observed_h or observed_cycles, optional scene-key "
                  "columns such as conditions.temperature_C) or of stored peaks (docs/fatigue.md §6)")
      ->required();
  cmd->add_option("--start", a->start, "Fatigue card to start from and keep for modes no test failed in "
                                       "(default: the built-in Report I card)");
  cmd->add_option("--out", a->out, "Fatigue card file to write (JSON; - = stdout)")->capture_default_str();
  cmd->add_option("--peaks-out", a->peaks_out,
                  "Also write the cases' peaks as an observed-lives CSV (fits again without running the scenes)");
  cmd->add_option("--plot", a->plot, "Also write the figure: S-N diagram per mode and predicted against observed "
                                     "lives (PNG)");
  cmd->add_flag("--fix-n", a->fix_n, "Hold n at the start card's value (fit sigma0 and b only)");
  cmd->add_flag("--fix-b", a->fix_b, "Hold b (1/degC) at the start card's value");
  add_json_flag(cmd, a->json, "the fitted card with its warnings, on stdout");
  add_verbosity_flags(cmd);  // --verbose: one line per life test as it runs
  cmd->callback([a] { run(*a); });
}

}  // namespace fitcli
