// fitcli's hyperelastic paths (hyperelastic.hpp).
#include "hyperelastic.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

#include "fitlib/card/hyperelastic.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "plot.hpp"

namespace fitcli {
namespace {

using fitlib::model::DeformationMode;

DeformationMode parse_mode(const std::string& text, const std::string& option) {
  if (const auto m = fitlib::model::deformation_mode_from_label(text)) return *m;
  throw fitlib::core::UsageError(option + ": unknown mode '" + text + "' (" + fitlib::model::kDeformationModeLabels + ")");
}

fitlib::data::QuasiStaticTable read_tables(const std::vector<std::string>& paths) {
  std::vector<fitlib::data::QuasiStaticTable> tables;
  for (const auto& p : paths) tables.push_back(fitlib::data::read_quasi_static_table(p));
  return fitlib::data::merge_quasi_static_tables(tables);
}

fitlib::card::HyperelasticCardOptions card_options(const HyperelasticFitArgs& a) {
  fitlib::card::HyperelasticCardOptions o;
  o.model = a.model;
  o.model_options = {{"compressible", a.compressible}};
  if (a.terms > 0) o.model_options["terms"] = a.terms;
  o.name = a.name;
  o.command = a.command_line;
  auto& f = o.fit;
  f.residual = fitlib::fit::parse_stress_residual(a.residual);
  f.multistart = a.multistart, f.max_iterations = a.max_iterations, f.seed = a.seed;
  for (const auto& w : a.mode_weights) {
    const auto eq = w.find('=');
    if (eq == std::string::npos) throw fitlib::core::UsageError("--mode-weight: expected MODE=WEIGHT, got '" + w + "'");
    const double value = std::stod(w.substr(eq + 1));
    if (!(value >= 0.0) || !std::isfinite(value)) throw fitlib::core::UsageError("--mode-weight: a weight is >= 0");
    f.mode_weights[parse_mode(w.substr(0, eq), "--mode-weight")] = value;
  }
  if (!a.stability_range.empty()) {
    if (a.stability_range.size() != 2 || !(a.stability_range[0] > 0.0 && a.stability_range[0] < 1.0) ||
        !(a.stability_range[1] > 1.0))
      throw fitlib::core::UsageError("--stability-range: MIN,MAX with 0 < MIN < 1 < MAX");
    f.stability_min_stretch = a.stability_range[0], f.stability_max_stretch = a.stability_range[1];
  }
  return o;
}

void print_summary(const fitlib::card::HyperelasticCardResult& r, const std::string& out_path) {
  const auto& f = r.result;
  std::ostream& out = summary();
  out << "model " << r.card.model_kind << " (" << r.card.model_options.dump() << "), backend ceres, " << f.starts
      << " start(s)\n";
  out << "points " << f.n_points << ", free parameters " << f.n_free << ", converged " << (f.converged ? "yes" : "no")
      << "\n";
  for (const auto& m : f.figures)
    out << "  " << fitlib::model::to_string(m.mode) << " (" << m.count << " points): rms relative error "
        << 100 * m.rms_rel_error << " %, mean " << 100 * m.mean_rel_error << " %, max " << 100 * m.max_rel_error
        << " % at " << fitlib::model::abscissa_name(m.mode) << " " << m.max_at << "\n";
  out << "verdict: "
      << (f.acceptable() ? "within the thresholds (docs/hyperelastic.md)"
                         : std::to_string(f.warnings.size()) + " warning(s) on stderr")
      << "\n";
  const auto& specs = f.model->parameters();
  for (std::size_t k = 0; k < f.values.size(); ++k) {
    out << "  " << specs[k].name << " = " << exact(f.values[k]) << " " << specs[k].unit;
    if (f.std_error[k]) out << "  ± " << *f.std_error[k] << "  [95 %: " << *f.ci95_low[k] << ", " << *f.ci95_high[k] << "]";
    else out << "  (" << f.std_error_reason[k] << ")";
    out << "\n";
  }
  out << "initial shear modulus " << f.model->hyperelastic()->initial_shear_modulus(f.values.data()) << " MPa\n";
  for (const auto& m : f.messages) note(m);
  if (!out_path.empty() && out_path != "-") out << "card written to " << out_path << "\n";
}

}  // namespace

void run_hyperelastic_fit(const HyperelasticFitArgs& a) {
  claim_output("--out", a.out, a.json);
  if (!a.plot.empty()) claim_png("--plot", a.plot);
  const auto paths = input_paths(a.data);
  const auto r = fitlib::card::fit_hyperelastic_card(read_tables(paths), card_options(a));
  if (!a.out.empty()) emit_with(a.out, [&](const std::string& path) { fitlib::card::save_card(path, r.card); });
  if (!a.plot.empty()) draw_figure(a.plot, [&] { plot_hyperelastic(r.card, paths, "", a.plot); });
  for (const auto& w : r.result.warnings) warning(w);
  if (a.json) {
    std::cout << fitlib::card::card_to_json(r.card).dump(2) << "\n";
    return;
  }
  print_summary(r, a.out);
}

void run_hyperelastic_eval(const fitlib::card::Card& card, const std::string& card_path, const std::string& mode_text,
                           const std::vector<double>& abscissae, const std::string& out, bool json) {
  const auto m = card.model();
  const auto p = card.values();
  const auto* law = m->hyperelastic();
  const DeformationMode mode = mode_text.empty() ? DeformationMode::uniaxial : parse_mode(mode_text, "--mode");
  const std::string x_name = fitlib::model::abscissa_name(mode);
  std::ostringstream csv;
  csv << "mode," << x_name << "," << (mode == DeformationMode::volumetric ? "pressure_MPa,cauchy_pressure_MPa"
                                                                          : "nominal_stress_MPa,cauchy_stress_MPa")
      << "\n";
  nlohmann::json rows = nlohmann::json::array();
  for (double x : abscissae) {
    if (const std::string why = law->outside_domain(p.data(), mode, x); !why.empty())
      throw fitlib::core::UsageError(why);
    const std::string at = std::string(" at ") + x_name + " " + exact(x);
    const double P = fitlib::core::require_finite(law->nominal_stress(p.data(), mode, x), "nominal stress" + at);
    const double sigma = fitlib::core::require_finite(law->cauchy_stress(p.data(), mode, x), "Cauchy stress" + at);
    csv << fitlib::model::to_string(mode) << "," << exact(x) << "," << exact(P) << "," << exact(sigma) << "\n";
    rows.push_back({{x_name, x}, {"nominal_stress_MPa", P}, {"cauchy_stress_MPa", sigma}});
  }
  if (const std::string q = fitlib::card::fit_quality_warning(card); !q.empty()) warning(q);
  if (json)
    emit(out, nlohmann::json{{"card", card_path}, {"mode", fitlib::model::to_string(mode)}, {"rows", rows}}.dump(2) + "\n");
  else
    emit(out, csv.str());
}

void plot_hyperelastic(const fitlib::card::Card& card, const std::vector<std::string>& data, const std::string& title,
                       const std::string& out) {
  const auto table = read_tables(data);
  const auto m = card.model();
  const auto p = card.values();
  const auto* law = m->hyperelastic();
  std::map<DeformationMode, std::vector<const fitlib::data::QuasiStaticRow*>> by_mode;
  for (const auto& r : table.rows)
    if (r.mode != DeformationMode::volumetric || law->compressible()) by_mode[r.mode].push_back(&r);
  write_png(out, [&](const std::string& tmp) {
    std::ostringstream s;
    s << "set terminal pngcairo size 1400,1000 enhanced font 'DejaVu Sans,11' linewidth 1.3\nset output '" << tmp
      << "'\nset grid lc rgb '#dddddd'\nset key inside left top box opaque font ',10'\n";
    const char* colours[] = {"#2c7bb6", "#d7191c", "#1a9641", "#7b3294", "#fdae61"};
    int g = 0;
    for (const auto& [mode, rows] : by_mode) {
      double lo = 1e300, hi = -1e300;
      s << "$d" << g << " << EOD\n";
      for (const auto* r : rows) {
        lo = std::min(lo, r->abscissa), hi = std::max(hi, r->abscissa);
        const double P = law->nominal_stress(p.data(), mode, r->abscissa);
        s << exact(r->abscissa) << " " << exact(r->stress_MPa) << " "
          << (r->stress_MPa != 0.0 ? exact(100.0 * (P / r->stress_MPa - 1.0)) : std::string("NaN")) << "\n";
      }
      s << "EOD\n$c" << g << " << EOD\n";
      const double from = std::min(lo, fitlib::model::undeformed_abscissa(mode));
      for (int k = 0; k <= 200; ++k) {
        const double x = from + (hi - from) * k / 200.0;
        if (law->outside_domain(p.data(), mode, x).empty())
          s << exact(x) << " " << exact(law->nominal_stress(p.data(), mode, x)) << "\n";
      }
      s << "EOD\n";
      ++g;
    }
    s << "set multiplot layout 2,1 title " << gnuplot_quoted((title.empty() ? card.name : title) +
                                                             " (" + card.model_kind + "; points: data, lines: card)")
      << " noenhanced font ',13'\nset xlabel 'stretch (simple shear: shear strain, volumetric: volume ratio)'\n"
      << "set ylabel 'nominal stress [MPa] (volumetric: pressure)'\nplot ";
    g = 0;
    for (const auto& [mode, rows] : by_mode) {
      const std::string c = std::string("lc rgb '") + colours[g % 5] + "'";
      s << (g ? ", " : "") << "$d" << g << " using 1:2 with points pt 7 ps 0.9 " << c << " title '"
        << fitlib::model::to_string(mode) << "', $c" << g << " using 1:2 with lines " << c << " notitle";
      ++g;
    }
    s << "\nset ylabel 'card / data - 1 [%]'\nunset key\nplot ";
    for (int k = 0; k < g; ++k)
      s << "$d" << k << " using 1:3 with linespoints pt 7 ps 0.7 lc rgb '" << colours[k % 5] << "' notitle, ";
    s << "0 with lines lc rgb 'black' dt 2 notitle\nunset multiplot\n";
    return s.str();
  });
}

}  // namespace fitcli
