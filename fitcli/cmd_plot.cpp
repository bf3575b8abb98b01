// fitcli plot: data against a card in one PNG (gnuplot, pngcairo; docs/fitting.md "Plots").
// Frequency data: storage, loss, tan δ and relative residuals, one colour per isotherm or
// temperature; relaxation data: M(t) and its residuals. The script and the data go to gnuplot on
// stdin; the PNG is written to a temporary beside --out and renamed.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include <unistd.h>

#include "commands.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "hyperelastic.hpp"
#include "fitlib/model/hyperelastic.hpp"

namespace fitcli {
namespace {

struct PlotArgs {
  std::vector<std::string> data;
  std::string card, out, format = "native", title;
  bool json = false;
};

// Rows of one isotherm (or one temperature), with the card's curve over its frequency range.
struct Group {
  std::string label;
  double temperature_C;
  std::vector<int> rows;
};

std::string temperature_label(double T) {
  char b[32];
  if (std::isnan(T)) return "T_{ref}";
  std::snprintf(b, sizeof b, "%.3g °C", T);
  return b;
}

// Groups rows by (set, temperature): `temperature(i)` and `set(i)` of row i of `count`.
template <typename Temperature, typename Set>
std::vector<Group> groups_by(int count, Temperature temperature, Set set) {
  std::map<std::pair<double, std::string>, std::vector<int>> by;
  for (int i = 0; i < count; ++i) {
    const double T = temperature(i);
    // Sets keep measured isotherms apart; rows without a set are grouped by rounded temperature.
    const double key = std::isnan(T) ? -1e9 : (set(i).empty() ? std::round(T) : 0.0);
    by[{key, set(i)}].push_back(i);
  }
  std::vector<Group> out;
  for (auto& [key, rows] : by) {
    double mean = 0.0;
    for (int r : rows) mean += temperature(r);
    mean /= rows.size();
    out.push_back({temperature_label(mean), mean, rows});
  }
  std::stable_sort(out.begin(), out.end(), [](const Group& a, const Group& b) {
    return (std::isnan(a.temperature_C) ? -1e9 : a.temperature_C) < (std::isnan(b.temperature_C) ? -1e9 : b.temperature_C);
  });
  return out;
}

std::vector<Group> groups_of(const fitlib::data::DynamicTestTable& t) {
  return groups_by(static_cast<int>(t.rows.size()), [&](int i) { return t.rows[i].condition.temperature_C; },
                   [&](int i) -> const std::string& { return t.rows[i].set; });
}

std::vector<Group> groups_of(const fitlib::data::RelaxationTable& t) {
  return groups_by(static_cast<int>(t.rows.size()), [&](int i) { return t.rows[i].temperature_C; },
                   [&](int i) -> const std::string& { return t.rows[i].set; });
}

// "lc palette frac …": group g of n, cold blue to hot red.
std::string palette_colour(int g, int n) {
  std::ostringstream c;
  c << "lc palette frac " << (n == 1 ? 0.0 : double(g) / (n - 1));
  return c.str();
}

const char* kHeader =
    "set terminal pngcairo size 1400,1000 enhanced font 'DejaVu Sans,11' linewidth 1.3\n"
    "set grid lc rgb '#dddddd'\nset key outside right top box opaque font ',9'\nset logscale x\n"
    "set format x '10^{%L}'\nset palette defined (0 '#2c7bb6', 0.5 '#ffbf00', 1 '#d7191c')\nunset colorbox\n";

// The card's 95 % confidence band (fit.confidence_band) as a data block $band: f, E′ low/high,
// E″ low/high, tan δ low/high; false when the card has none.
bool band_block(const nlohmann::json& fit, std::ostringstream& s) {
  const auto b = fit.find("confidence_band");
  if (b == fit.end() || !b->is_object() || !b->contains("frequency_Hz")) return false;
  const auto& f = (*b)["frequency_Hz"];
  s << "$band << EOD\n";
  for (std::size_t k = 0; k < f.size(); ++k) {
    s << exact(f[k].get<double>());
    for (const char* c : {"storage_low_MPa", "storage_high_MPa", "loss_low_MPa", "loss_high_MPa", "tan_delta_low",
                          "tan_delta_high"})
      s << " " << exact((*b)[c][k].get<double>());
    s << "\n";
  }
  s << "EOD\n";
  return true;
}

// What the title adds from the card's verdict: where the data are not Kramers–Kronig consistent,
// each range of fit.quality.kramers_kronig_inconsistent_Hz (a list of [lo, hi]; older cards hold
// one pair, their envelope).
std::string kramers_kronig_note(const nlohmann::json& fit) {
  const auto q = fit.find("quality");
  if (q == fit.end() || !q->contains("kramers_kronig_inconsistent_Hz")) return "";
  nlohmann::json ranges = (*q)["kramers_kronig_inconsistent_Hz"];
  if (!ranges.is_array() || ranges.empty()) return "";
  if (ranges[0].is_number()) ranges = nlohmann::json::array({ranges});
  std::string note = "; data Kramers-Kronig inconsistent";
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    char b[80];
    std::snprintf(b, sizeof b, "%s %.3g to %.3g Hz", k ? "," : "", ranges[k][0].get<double>(), ranges[k][1].get<double>());
    note += b;
  }
  return note;
}

// Storage, loss, tan δ, residuals; `mode_letter` E or G; the card's band shaded where it has one.
std::string frequency_script(const fitlib::data::DynamicTestTable& t, const fitlib::model::Model& model,
                             const std::vector<double>& p, const std::string& title, const std::string& png,
                             const nlohmann::json& fit) {
  const auto groups = groups_of(t);
  const std::string M = t.rows.front().condition.mode == fitlib::model::TestMode::shear ? "G" : "E";
  std::ostringstream s;
  s << kHeader << "set output '" << png << "'\n";
  const int n = static_cast<int>(groups.size());
  for (int g = 0; g < n; ++g) {
    s << "$d" << g << " << EOD\n";
    double fmin = HUGE_VAL, fmax = 0.0;
    for (int r : groups[g].rows) {
      const auto& row = t.rows[r];
      const auto m = model.moduli(p.data(), row.condition);
      fmin = std::min(fmin, row.condition.frequency_Hz);
      fmax = std::max(fmax, row.condition.frequency_Hz);
      s << exact(row.condition.frequency_Hz) << " " << exact(row.storage_MPa) << " " << exact(row.loss_MPa) << " "
        << exact(row.loss_MPa / row.storage_MPa) << " " << exact(100.0 * (m.storage / row.storage_MPa - 1.0)) << " "
        << exact(100.0 * (m.loss / row.loss_MPa - 1.0)) << "\n";
    }
    s << "EOD\n$c" << g << " << EOD\n";
    const int points = std::max(2, static_cast<int>(20.0 * std::log10(fmax / fmin)) + 1);  // 20 per decade
    for (int k = 0; k < points; ++k) {
      auto c = t.rows[groups[g].rows.front()].condition;
      c.frequency_Hz = fmin * std::pow(fmax / fmin, points == 1 ? 0.0 : double(k) / (points - 1));
      const auto m = model.moduli(p.data(), c);
      s << exact(c.frequency_Hz) << " " << exact(m.storage) << " " << exact(m.loss) << " " << exact(m.loss / m.storage)
        << "\n";
    }
    s << "EOD\n";
  }
  const bool band = n == 1 && band_block(fit, s);  // the band is at one temperature
  const auto colour = [&](int g) { return palette_colour(g, n); };
  const auto panel = [&](const std::string& ylabel, int column, bool logy, int curve_column) {
    s << (logy ? "set logscale y\nset format y '10^{%L}'\n" : "unset logscale y\nset format y '%g'\n");
    s << "set xlabel 'frequency f [Hz]'\nset ylabel \"" << ylabel << "\"\nplot ";
    if (band)
      s << "$band using 1:" << 2 * column - 2 << ":" << 2 * column - 1
        << " with filledcurves fs transparent solid 0.35 noborder lc rgb '#7f7f7f' title '95 % band', ";
    for (int g = 0; g < n; ++g) {
      s << (g ? ", " : "") << "$d" << g << " using 1:" << column << " with points pt 7 ps 0.6 " << colour(g)
        << " title '" << groups[g].label << "'";
      if (curve_column > 0)
        s << ", $c" << g << " using 1:" << curve_column << " with lines " << colour(g) << " notitle";
    }
    s << "\n";
  };
  s << "set multiplot layout 2,2 title "
    << gnuplot_quoted(title + " (points: data, lines: card" + (band ? ", shade: 95 % band" : "") + ")" +
                      kramers_kronig_note(fit))
    << " noenhanced font ',13'\n";
  panel("storage modulus " + M + "' [MPa]", 2, true, 2);
  panel("loss modulus " + M + "'' [MPa]", 3, true, 3);
  panel("loss factor tan {/Symbol d} [-]", 4, true, 4);
  // Residuals: filled E', open E'', coloured as above; the key names only the symbols.
  s << "unset logscale y\nset format y '%g'\nset ylabel 'card / data - 1 [%]'\nset xlabel 'frequency f [Hz]'\nplot ";
  for (int g = 0; g < n; ++g)
    s << "$d" << g << " using 1:5 with points pt 7 ps 0.5 " << colour(g) << " notitle, $d" << g
      << " using 1:6 with points pt 6 ps 0.5 " << colour(g) << " notitle, ";
  s << "NaN with points pt 7 lc rgb 'gray30' title \"" << M << "'\", NaN with points pt 6 lc rgb 'gray30' title \""
    << M << "''\", 0 with lines lc rgb 'black' dt 2 notitle\nunset multiplot\n";
  return s.str();
}

// M(t) per isotherm (data and the card at the isotherm's temperature) and the residuals.
std::string relaxation_script(const fitlib::data::RelaxationTable& t, const fitlib::model::Model& model,
                              const std::vector<double>& p, const std::string& title, const std::string& png) {
  const auto groups = groups_of(t);
  const int n = static_cast<int>(groups.size());
  const std::string M = t.rows.front().mode == fitlib::model::TestMode::shear ? "G" : "E";
  std::ostringstream s;
  s << kHeader << "set output '" << png << "'\n";
  for (int g = 0; g < n; ++g) {
    fitlib::model::TestCondition c;
    c.mode = t.rows.front().mode;
    double tmin = HUGE_VAL, tmax = 0.0;
    s << "$d" << g << " << EOD\n";
    for (int r : groups[g].rows) {
      const auto& row = t.rows[r];
      c.temperature_C = row.temperature_C;
      const double m = model.relaxation_modulus(p.data(), c, row.time_s);
      tmin = std::min(tmin, row.time_s);
      tmax = std::max(tmax, row.time_s);
      s << exact(row.time_s) << " " << exact(row.modulus_MPa) << " " << exact(100.0 * (m / row.modulus_MPa - 1.0)) << "\n";
    }
    s << "EOD\n$c" << g << " << EOD\n";
    c.temperature_C = groups[g].temperature_C;
    const int points = std::max(2, static_cast<int>(20.0 * std::log10(tmax / tmin)) + 1);  // 20 per decade
    for (int k = 0; k < points; ++k) {
      const double time = tmin * std::pow(tmax / tmin, double(k) / (points - 1));
      s << exact(time) << " " << exact(model.relaxation_modulus(p.data(), c, time)) << "\n";
    }
    s << "EOD\n";
  }
  s << "set multiplot layout 2,1 title " << gnuplot_quoted(title + " (points: data, lines: card)")
    << " noenhanced font ',13'\nset xlabel 'time t [s]'\n"
    << "set logscale y\nset format y '10^{%L}'\nset ylabel 'relaxation modulus " << M << "(t) [MPa]'\n"
    // One entry: the key inside; more: outside in a right margin both panels keep (one width).
    << (n == 1 ? "set key inside right top box opaque\n" : "set rmargin at screen 0.86\n") << "plot ";
  for (int g = 0; g < n; ++g)
    s << (g ? ", " : "") << "$d" << g << " using 1:2 with points pt 7 ps 0.6 " << palette_colour(g, n) << " title '"
      << groups[g].label << "', $c" << g << " using 1:2 with lines " << palette_colour(g, n) << " notitle";
  // The residual panel names nothing (the colours are the panel above's): no empty key box.
  s << "\nunset logscale y\nset format y '%g'\nset ylabel 'card / data - 1 [%]'\n"
    << "unset key\nplot ";
  for (int g = 0; g < n; ++g)
    s << "$d" << g << " using 1:3 with points pt 7 ps 0.5 " << palette_colour(g, n) << " notitle, ";
  s << "0 with lines lc rgb 'black' dt 2 notitle\nunset multiplot\n";
  return s.str();
}

}  // namespace

std::string gnuplot_quoted(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

namespace {

// Whether the shell popen runs would find gnuplot: an executable file named gnuplot in a folder of
// PATH (an empty entry is the current folder; no PATH: the shell's default folders).
bool gnuplot_on_path() {
  const char* env = std::getenv("PATH");
  const std::string path = env ? env : "/usr/local/bin:/usr/bin:/bin";
  for (std::size_t begin = 0;;) {
    const std::size_t end = path.find(':', begin);
    const std::string dir = path.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    const std::string exe = (dir.empty() ? std::string(".") : dir) + "/gnuplot";
    std::error_code ec;
    if (::access(exe.c_str(), X_OK) == 0 && !std::filesystem::is_directory(exe, ec)) return true;
    if (end == std::string::npos) return false;
    begin = end + 1;
  }
}

bool& figure_failed() {
  static bool failed = false;
  return failed;
}

}  // namespace

void claim_png(const std::string& option, const std::string& path, const std::string& folder_made_later) {
  namespace fs = std::filesystem;
  if (path == "-") throw fitlib::core::UsageError(option + ": a PNG needs a file (- would be stdout)");
  if (path.find('\'') != std::string::npos)
    throw fitlib::core::UsageError(option + ": the PNG file name must not contain a quote");
  const auto normal = [](fs::path p) { return (fs::absolute(p.empty() ? "." : p) / "").lexically_normal(); };
  const bool in_made_folder = !folder_made_later.empty() && !fs::exists(folder_made_later) &&
                              normal(fs::path(path).parent_path()) == normal(folder_made_later);
  if (!in_made_folder) fitlib::core::check_output_path(path);
  if (!gnuplot_on_path())
    throw FigureError(option + " " + path + ": gnuplot is not on PATH (install the Debian package gnuplot-nox, or "
                      "leave out " + option + "); nothing was run or written");
}

bool draw_figure(const std::string& png, const std::function<void()>& draw) {
  try {
    draw();
    return true;
  } catch (const FigureError& e) {
    figure_failed() = true;
    warning(std::string(e.what()) + "; the figure " + png + " was not written, the run's other outputs are (exit 5)");
    return false;
  }
}

bool figure_not_drawn() { return figure_failed(); }

void write_png(const std::string& out, const std::function<std::string(const std::string& tmp)>& make_script) {
  claim_png("plot", out);  // callers claim it before the work; a library caller is checked here
  // Beside the file written: a link's target, whose folder check_output_path checked.
  const std::string tmp = fitlib::core::resolve_links(out) + ".tmp-" + std::to_string(getpid()) + ".png";
  const std::string script = make_script(tmp);
  FILE* pipe = popen("gnuplot 1>&2", "w");
  if (!pipe) throw FigureError("plot: cannot start gnuplot");
  // gnuplot speaks on stderr (stdout may be --json's). A shell that finds no gnuplot exits at
  // once: writing must not kill us with SIGPIPE.
  const auto previous = std::signal(SIGPIPE, SIG_IGN);
  std::fwrite(script.data(), 1, script.size(), pipe);
  const int status = pclose(pipe);
  std::signal(SIGPIPE, previous);
  if (status != 0) {
    std::remove(tmp.c_str());
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
      throw FigureError("plot: gnuplot not found (install the Debian package gnuplot-nox)");
    throw FigureError("plot: gnuplot failed (" +
                      (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                         : "wait status " + std::to_string(status)) + ")");
  }
  // Through core's writer, not a rename of its own: a --plot on a device or FIFO (/dev/full) is
  // written in place and its write checked; a rename replaced the device by a file (as root).
  const std::string png = fitlib::core::read_file(tmp);
  std::remove(tmp.c_str());
  fitlib::core::write_file_atomically(out, png);
}

void plot_card(const fitlib::card::Card& card, const std::vector<std::string>& data, const std::string& format,
               const std::string& title, const std::string& out) {
  using namespace fitlib;
  const auto model = card.model();
  const auto p = card.values();
  const std::string shown = title.empty() ? card.name : title;
  if (model->hyperelastic()) return plot_hyperelastic(card, data, title, out);
  write_png(out, [&](const std::string& tmp) {
    if (is_relaxation_data(data, format)) return relaxation_script(read_relaxation_tables(data), *model, p, shown, tmp);
    data::ReadOptions read;
    read.format = format == "pyvisco" ? data::TableFormat::pyvisco : data::TableFormat::native;
    return frequency_script(read_tables(data, format, read), *model, p, shown, tmp, card.fit);
  });
}

namespace {

void run_plot(const PlotArgs& a) {
  claim_png("--out", a.out);
  const auto card = fitlib::card::load_card(input_path(a.card));
  plot_card(card, input_paths(a.data), a.format, a.title, a.out);
  if (a.json)
    std::cout << nlohmann::json{{"card", a.card}, {"data", a.data}, {"out", a.out}}.dump(2) << "\n";
  else
    detail("wrote " + a.out);
}

}  // namespace

void register_plot(CLI::App& app) {
  auto a = std::make_shared<PlotArgs>();
  auto* cmd = app.add_subcommand("plot", "Plot data against a card (PNG via gnuplot): E', E'', tan delta, residuals");
  cmd->add_option("--data", a->data,
                  "Data file(s): dynamic-test CSV, pyvisco CSV (frequency or time), EPLEXOR .xls (- = stdin)")
      ->required();
  cmd->add_option("--card", a->card, "Material card file (JSON; - = stdin)")->required();
  cmd->add_option("--out", a->out, "PNG file to write (atomically)")->required();
  cmd->add_option("--format", a->format, "native | pyvisco | eplexor")->capture_default_str()
      ->check(CLI::IsMember({"native", "pyvisco", "eplexor"}));
  cmd->add_option("--title", a->title, "Figure title (default: the card's name)");
  add_json_flag(cmd, a->json, "the files read and written, on stdout");
  add_verbosity_flags(cmd);
  cmd->callback([a] { run_plot(*a); });
}

}  // namespace fitcli
