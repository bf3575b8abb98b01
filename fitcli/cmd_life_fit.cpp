// fitcli life-fit: the life constants σ0, n, b of (6.31) per failure mode fitted to observed belt
// lives — a list of drive scenes with observed hours and failure modes (each scene run to its
// stresses) or stored peaks — written as a fatigue card with 95 % intervals (docs/fatigue.md §6).
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

namespace fitcli {
namespace {

struct LifeFitArgs {
  std::string observed, start, out = "life-card.json", peaks_out;
  bool fix_b = false, json = false;
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
  t << std::left << std::setw(14) << "mode" << std::setw(7) << "cases" << std::setw(28) << "sigma0_MPa [95 %]"
    << std::setw(28) << "n [95 %]" << std::setw(28) << "b_per_C [95 %]" << "rms log10\n";
  for (const auto& f : r.fits) {
    t << std::setw(14) << fitlib::fatigue::to_string(f.mode) << std::setw(7) << f.cases;
    for (const auto& c : f.constants) t << std::setw(28) << with_interval(c);
    t << sig4(f.rms_log10_error) << "\n";
    if (!f.note.empty()) t << "  note: " << f.note << "\n";
  }
  for (const std::string& w : r.warnings) t << "WARNING: " << w << "\n";
  return t.str();
}

void run(const LifeFitArgs& a) {
  claim_output("--out", a.out, a.json);
  if (!a.peaks_out.empty()) claim_output("--peaks-out", a.peaks_out, a.json);
  const fitlib::fatigue::FatigueCard start =
      a.start.empty() ? fitlib::fatigue::default_card() : fitlib::fatigue::load_card(a.start);
  const std::string text = fitlib::core::read_file(input_path(a.observed));
  const std::string source = a.observed == "-" ? "stdin" : a.observed;  // stdin: scenes from the current folder
  const auto cases = fitlib::scene::observed_cases(
      text, source, start, [](const fitlib::scene::LifeTest& t, std::size_t k, std::size_t n) {
        detail("life test " + std::to_string(k) + "/" + std::to_string(n) + ": " + t.name + " (" + t.scene_path + ")");
      });
  fitlib::fatigue::LifeCardFit fit = fitlib::fatigue::fit_life_card(cases, start, a.fix_b);
  fit.card.name = "life constants fitted to " + source;
  fit.card.provenance["observed"] = {
      {"file", source}, {"sha256", fitlib::core::sha256_hex(text)}, {"cases", cases.size()}};
  fit.card.provenance["start_file"] = a.start.empty() ? "built-in: fatigue::default_card()" : a.start;
  fit.card.provenance["command"] = with_stdin_named(command_line());
  if (!a.peaks_out.empty()) emit(a.peaks_out, fitlib::fatigue::observed_lives_csv(cases));
  emit_with(a.out, [&](const std::string& path) { fitlib::fatigue::save_card(path, fit.card); });
  if (a.json) {
    nlohmann::json j = fitlib::fatigue::card_to_json(fit.card);
    j["warnings"] = fit.warnings;
    std::cout << j.dump(2) << "\n";
    return;
  }
  summary() << fit_table(fit);
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
  cmd->add_flag("--fix-b", a->fix_b, "Hold b (1/degC) at the start card's value");
  add_json_flag(cmd, a->json, "the fitted card with its warnings, on stdout");
  add_verbosity_flags(cmd);  // --verbose: one line per life test as it runs
  cmd->callback([a] { run(*a); });
}

}  // namespace fitcli
