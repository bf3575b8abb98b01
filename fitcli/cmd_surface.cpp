// fitcli surface fit | eval | grid: Bezier surfaces of measured data and of cards (docs/formats.md §4, §6).
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>
#include <tuple>
#include <optional>

#include "commands.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/json.hpp"
#include "fitlib/surface/card_grid.hpp"
#include "fitlib/surface/fit.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "window_check.hpp"

namespace fitcli {
namespace {

using namespace fitlib;

// Unit from a column name's suffix (frequency_Hz → Hz, temperature_C → C, storage_MPa → MPa).
std::string unit_from_name(const std::string& name) {
  if (name.size() > 6 && name.compare(name.size() - 6, 6, "_rad_s") == 0) return "rad/s";
  const auto underscore = name.rfind('_');
  if (underscore == std::string::npos) return "";
  const std::string suffix = name.substr(underscore + 1);
  for (const char* unit : {"Hz", "C", "K", "Pa", "kPa", "MPa", "GPa", "s", "mm", "N"})
    if (suffix == unit) return suffix;
  return "";
}

std::string stats_text(const surface::Surface& s) {
  std::ostringstream out;
  out.precision(6);
  const auto& st = s.statistics;
  out << "surface of " << s.dependent_name << (s.dependent_transform == surface::Transform::log10 ? " (fitted as log10)" : "") << " over";
  for (const auto& a : s.axes)
    out << " " << a.name << " (" << surface::to_string(a.transform) << ", degree " << a.degree << ", "
        << a.level_count << (a.scattered ? " distinct values" : " levels") << ", [" << a.start << ", "
        << a.end << "])";
  out << "\nN = " << st.n_points << ", p = " << st.n_parameters << ", residual dof = " << st.residual_dof
      << ", R = " << st.R << ", s = " << (std::isfinite(st.s) ? core::format_number(st.s, 6) : "undefined (no residual dof)")
      << ", max relative error = " << 100 * st.max_relative_error
      << " % (data row " << st.max_relative_error_row + 1 << ")\n";
  if (s.level_grid) out << "empty cells of the level grid: " << s.missing_cells.size() << "\n";
  for (const auto& g : s.constraints)
    out << "constraint [" << g.origin << "] " << g.description << " (" << g.equations.size()
        << " equation(s), " << g.cells.size() << " cell(s))\n";
  return out.str();
}

// ---- surface fit ----
struct FitArgs {
  std::string data, y, constraints, missing, out, name, plot;
  std::vector<std::string> x;
  std::vector<int> degrees;
  double level_tolerance = 0.05;
  bool json = false;
};

// "COL" or "COL:TRANSFORM" of --x and --y: the column and the transform, if given (parse_transform's
// UsageError for an unknown one).
std::pair<std::string, std::optional<surface::Transform>> column_spec(const std::string& spec) {
  const auto colon = spec.find(':');
  if (colon == std::string::npos) return {spec, std::nullopt};
  return {spec.substr(0, colon), surface::parse_transform(spec.substr(colon + 1))};
}

void run_fit(const FitArgs& a) {
  surface::FitOptions options;
  std::vector<std::string> columns;
  for (const auto& spec : a.x) {
    surface::AxisSpec axis;
    std::tie(axis.name, axis.transform) = column_spec(spec);
    axis.unit = unit_from_name(axis.name);
    columns.push_back(axis.name);
    options.axes.push_back(axis);
  }
  if (!a.degrees.empty()) {
    if (a.degrees.size() != options.axes.size())
      throw core::UsageError("--degree needs one value per --x (" + std::to_string(options.axes.size()) + ")");
    for (std::size_t k = 0; k < a.degrees.size(); ++k) options.axes[k].degree = a.degrees[k];
  }
  try {
    const auto [name, transform] = column_spec(a.y);
    options.dependent_name = name;
    options.dependent_transform = transform.value_or(surface::Transform::linear);
  } catch (const core::UsageError& e) {
    throw core::UsageError("--y " + a.y + ": " + e.what() + "; COL:log fits log10 of the values");
  }
  options.dependent_unit = unit_from_name(options.dependent_name);
  options.name = a.name;
  options.level_tolerance = a.level_tolerance;
  // With user constraints the user takes charge of missing cells unless --missing says otherwise.
  options.missing = surface::parse_missing_cell_remedy(
      !a.missing.empty() ? a.missing : a.constraints.empty() ? "constrain" : "none");
  if (!a.constraints.empty()) {
    options.user_constraints = surface::read_user_constraints(input_path(a.constraints));
    options.user_constraints_source = a.constraints;
  }
  claim_output("--out", a.out, false);
  if (!a.plot.empty()) claim_png("--plot", a.plot);
  const std::string data_path = input_path(a.data);
  const auto data = surface::read_sample_columns(data_path, columns, options.dependent_name);
  surface::Surface s = surface::fit_surface(data, options);
  s.provenance = {{"data_files", {with_stdin_named(data_path)}},
                  {"data_sha256", core::sha256_hex(core::read_file(data_path))},
                  {"fitlib_version", FITLIB_VERSION},
                  {"command", command_line()}};
  for (const std::string& w : surface::statistics_warnings(s)) warning(w);
  // The figure first (a scattered axis is a usage error before anything is written); if gnuplot
  // fails, the surface is still written (exit 5).
  if (!a.plot.empty())
    draw_figure(a.plot, [&] {
      write_png(a.plot, [&](const std::string& tmp) { return surface_plot_script(s, data, tmp); });
    });
  const std::string document = surface::surface_to_json(s).dump(2) + "\n";
  if (a.out.empty() || a.out == "-") {
    emit("", document);
    return;
  }
  surface::save_surface(a.out, s);
  if (a.json)
    emit("", surface::surface_to_json(s)["statistics"].dump(2) + "\n");
  else
    emit("", stats_text(s));
}

// ---- surface eval ----
struct EvalArgs {
  std::string surface, points, out;
  std::vector<std::string> at;
  bool allow_extrapolation = false, gradient = false, json = false;
};

std::vector<double> parse_point(const std::string& text, std::size_t n) {
  std::vector<double> x;
  std::stringstream in(text);
  std::string field;
  while (std::getline(in, field, ',')) {
    char* stop = nullptr;
    const double v = std::strtod(field.c_str(), &stop);
    if (field.empty() || *stop != '\0' || !std::isfinite(v))
      throw core::UsageError("--at '" + text + "': '" + field + "' is not a number");
    x.push_back(v);
  }
  if (x.size() != n)
    throw core::UsageError("--at '" + text + "' has " + std::to_string(x.size()) + " values; the surface has " +
                           std::to_string(n) + " axes");
  return x;
}

void run_eval(const EvalArgs& a) {
  claim_output("--out", a.out, false);
  const auto s = surface::load_surface(input_path(a.surface));
  // Said wherever the surface is read, as a card's failed quality verdict is.
  if (const std::string range = surface::range_warning(s); !range.empty()) warning(range + " (" + a.surface + ")");
  const std::size_t n = s.dimension();
  std::vector<std::vector<double>> points;
  for (const auto& text : a.at) points.push_back(parse_point(text, n));
  if (!a.points.empty()) {
    std::vector<std::string> names;
    for (const auto& axis : s.axes) names.push_back(axis.name);
    // the first axis doubles as the (unused) y column: read_sample_columns wants one
    const auto table = surface::read_sample_columns(input_path(a.points), names, names.front());
    for (Eigen::Index r = 0; r < table.x.rows(); ++r) {
      std::vector<double> x(n);
      for (std::size_t k = 0; k < n; ++k) x[k] = table.x(r, static_cast<Eigen::Index>(k));
      points.push_back(x);
    }
  }
  if (points.empty()) throw core::UsageError("surface eval needs --at or --points");

  std::ostringstream csv;
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& axis : s.axes) csv << axis.name << ",";
  csv << s.dependent_name;
  if (a.gradient)
    for (const auto& axis : s.axes) csv << ",d_" << s.dependent_name << "_d_" << axis.name;
  csv << ",extrapolated\n";
  for (const auto& x : points) {
    auto e = s.evaluate(x.data(), a.allow_extrapolation);
    const std::string at = " at " + exact_list(x) + " (control points of " + a.surface + " too large?)";
    core::require_finite(e.value, s.dependent_name + at);
    for (Eigen::Index k = 0; k < e.gradient.size(); ++k)
      core::require_finite(e.gradient[k], "d " + s.dependent_name + " / d " + s.axes[k].name + at);
    for (double v : x) csv << exact(v) << ",";
    csv << exact(e.value);
    if (a.gradient)
      for (Eigen::Index k = 0; k < e.gradient.size(); ++k) csv << "," << exact(e.gradient[k]);
    csv << "," << (e.extrapolated ? 1 : 0) << "\n";
    nlohmann::json row = {{"at", x}, {"value", e.value}, {"extrapolated", e.extrapolated}};
    if (a.gradient)
      row["gradient"] = std::vector<double>(e.gradient.data(), e.gradient.data() + e.gradient.size());
    rows.push_back(row);
  }
  if (a.json)
    emit(a.out, nlohmann::json{{"surface", a.surface}, {"dependent", s.dependent_name}, {"rows", rows}}.dump(2) + "\n");
  else
    emit(a.out, csv.str());
}

// ---- surface grid ----
struct GridArgs {
  std::string card, mode = "shear", orientation, out, surface_out, quantity = "storage", plot;
  std::vector<double> frequency_Hz, temperature_C, amplitude;
  std::vector<int> degrees;
  bool json = false, allow_extrapolation = false;
};

// Every grid point within the card's data window, or --allow-extrapolation (as eval).
void check_grid_window(const GridArgs& a, const fitlib::card::Card& card) {
  const std::vector<double> temperatures = a.temperature_C.empty() ? std::vector<double>{NAN} : a.temperature_C;
  const std::vector<double> amplitudes = a.amplitude.empty() ? std::vector<double>{0.0} : a.amplitude;
  WindowCheck window("surface grid", a.card, card, temperatures, a.allow_extrapolation);
  fitlib::model::TestCondition c;
  c.mode = fitlib::model::parse_test_mode(a.mode);
  c.orientation = a.orientation;
  for (double T : temperatures)
    for (double amp : amplitudes)
      for (double f : a.frequency_Hz) {
        c.temperature_C = T, c.strain_amplitude = amp, c.frequency_Hz = f;
        window.beyond(c);
      }
}

void run_grid(const GridArgs& a) {
  // Every output is checked before the work and written after it: no partial results.
  claim_output("--out", a.out, false);
  claim_output("--surface-out", a.surface_out, false);
  if (!a.plot.empty() && a.surface_out.empty())
    throw core::UsageError("--plot draws the grid's surface: give --surface-out too");
  if (!a.plot.empty()) claim_png("--plot", a.plot);
  const auto card = card::load_card(input_path(a.card));
  check_grid_window(a, card);
  surface::CardGridRequest request;
  request.mode = model::parse_test_mode(a.mode);
  request.orientation = a.orientation;
  request.frequency_Hz = a.frequency_Hz;
  request.temperature_C = a.temperature_C;
  request.strain_amplitude = a.amplitude;
  const auto grid = surface::evaluate_card_grid(card, request);
  const std::string grid_csv = surface::modulus_grid_csv(grid);
  if (!a.surface_out.empty()) {
    auto s = surface::surface_from_grid(grid, a.quantity, a.degrees);
    s.provenance["card_file"] = a.card;
    s.provenance["fitlib_version"] = FITLIB_VERSION;
    s.provenance["command"] = command_line();
    emit_with(a.surface_out, [&](const std::string& path) { surface::save_surface(path, s); });
    // (The grid surface interpolates its points by design: no residual-dof warning, only the range.)
    if (const std::string range = surface::range_warning(s); !range.empty()) warning(range);
    if (!a.plot.empty())
      draw_figure(a.plot, [&] {
        write_png(a.plot, [&](const std::string& tmp) {
          return surface_plot_script(s, surface::grid_samples(grid, a.quantity), tmp);
        });
      });
    std::ostringstream text;
    text.precision(4);
    text << "surface of " << s.dependent_name << ": N = " << s.statistics.n_points << ", p = "
         << s.statistics.n_parameters << ", max relative error at the grid points = "
         << 100 * s.statistics.max_relative_error << " %";
    note(text.str());
  }
  if (a.json)
    emit(a.out, nlohmann::json{{"card", a.card}, {"rows", csv_rows_json(grid_csv)}}.dump(2) + "\n");
  else
    emit(a.out, grid_csv);
}

}  // namespace

void register_surface(CLI::App& app) {
  auto* surface_cmd = app.add_subcommand("surface", "Bezier tensor-product surfaces: fit, eval, grid");
  surface_cmd->require_subcommand(1);
  add_verbosity_flags(surface_cmd);

  auto fa = std::make_shared<FitArgs>();
  auto* fit = surface_cmd->add_subcommand("fit", "Fit a surface to measured points (least squares on control points)");
  fit->add_option("--data", fa->data, "Data file: CSV with a header row (- = stdin)")->required();
  fit->add_option("--x", fa->x, "Independent column, COL or COL:log / COL:lin (repeat; order = axis order)")
      ->required();
  fit->add_option("--y", fa->y, "Dependent column, COL or COL:log (fit log10 of positive values, e.g. moduli over decades)")->required();
  fit->add_option("--degree", fa->degrees, "Degree per axis, comma separated (default: levels - 1, at most 6)")
      ->delimiter(',');
  fit->add_option("--constraints", fa->constraints, "Constraints file: JSON of linear constraints on control points");
  fit->add_option("--missing", fa->missing,
                  "Remedy for missing cells: constrain | lower-degree | none (default constrain; none with --constraints)");
  fit->add_option("--level-tolerance", fa->level_tolerance,
                  "Values closer than this fraction of an axis range form one level (0: every value)")
      ->capture_default_str();
  fit->add_option("--name", fa->name, "Name stored in the surface");
  fit->add_option("--plot", fa->plot,
                  "Also write the figure (PNG): the surface along each axis through the data's level combinations, "
                  "with the data");
  fit->add_option("--out", fa->out, "Surface file to write (JSON; default or - = stdout)");
  add_json_flag(fit, fa->json, "the statistics on stdout (with --out; without it the surface is the document)");
  add_verbosity_flags(fit);
  fit->callback([fa] { run_fit(*fa); });

  auto ea = std::make_shared<EvalArgs>();
  auto* eval = surface_cmd->add_subcommand("eval", "Evaluate a surface (value, optional gradient)");
  eval->add_option("--surface", ea->surface, "Surface file (JSON; - = stdin)")->required();
  eval->add_option("--at", ea->at, "Point V1,V2,... in axis order (repeat for more points)");
  eval->add_option("--points", ea->points, "Points file: CSV with one column per axis name (- = stdin)");
  eval->add_flag("--allow-extrapolation", ea->allow_extrapolation,
                 "Evaluate outside the fitted interval (rows are flagged extrapolated = 1)");
  eval->add_flag("--gradient", ea->gradient, "Add the derivatives along each axis");
  eval->add_option("--out", ea->out, "Output file (CSV, or JSON with --json; default or - = stdout)");
  add_json_flag(eval, ea->json, "the rows instead of CSV, on stdout or in --out");
  add_verbosity_flags(eval);
  eval->callback([ea] { run_eval(*ea); });

  auto ga = std::make_shared<GridArgs>();
  auto* grid = surface_cmd->add_subcommand("grid", "Modulus grid of a card (CSV for FE codes) and its surface");
  grid->add_option("--card", ga->card, "Material card file (JSON; - = stdin)")->required();
  grid->add_option("--frequency-hz", ga->frequency_Hz, "Frequencies in Hz, comma separated")
      ->required()->delimiter(',')->check(positive_number());
  grid->add_option("--temperature-c", ga->temperature_C, "Temperatures in degC (default: card reference)")
      ->delimiter(',')->check(temperature_c_range());
  grid->add_option("--amplitude", ga->amplitude, "Strain amplitudes (default: small-amplitude limit)")
      ->delimiter(',')->check(strain_amplitude_range());
  grid->add_flag("--allow-extrapolation", ga->allow_extrapolation,
                 "Evaluate beyond the card's data window (a warning; without it such a grid is refused)");
  grid->add_option("--mode", ga->mode, "shear | uniaxial | bulk")->capture_default_str();
  grid->add_option("--orientation", ga->orientation, "Thesis orientation label");
  grid->add_option("--quantity", ga->quantity, "Surface quantity: storage | loss | tan_delta | mean")
      ->capture_default_str();
  grid->add_option("--degree", ga->degrees, "Surface degree per axis present (amplitude, frequency, temperature)")
      ->delimiter(',');
  grid->add_option("--out", ga->out, "Grid file to write (CSV, or JSON with --json; default or - = stdout)");
  grid->add_option("--surface-out", ga->surface_out, "Also fit a surface of --quantity and write it to this file (JSON)");
  grid->add_option("--plot", ga->plot, "With --surface-out: also draw that surface through the grid (PNG)");
  add_json_flag(grid, ga->json, "the grid rows instead of CSV, on stdout or in --out");
  add_verbosity_flags(grid);
  grid->callback([ga] { run_grid(*ga); });
}

}  // namespace fitcli
