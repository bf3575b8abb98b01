// fitcli export: FE-solver material keywords from a card (docs/cli.md "export", docs/formats.md §3).
#include <cmath>
#include <limits>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "fitlib/card/export.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "window_check.hpp"

namespace fitcli {

// "abaqus | ansys | lsdyna" with each format's term limit, from the library's one table.
std::string export_formats_text() {
  std::string text;
  for (const auto& f : fitlib::card::export_formats()) {
    const int cap = fitlib::card::max_prony_terms(f);
    text += (text.empty() ? "" : ", ") + f + (cap > 0 ? " (at most " + std::to_string(cap) + " Prony terms)" : "");
  }
  return text;
}

void register_export(CLI::App& app) {
  struct Args {
    std::string card, format, out;
    bool json = false, allow_extrapolation = false;
    fitlib::card::ExportOptions options;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("export", "Write a card as FE-solver material keywords: " + export_formats_text());
  cmd->add_option("--card", args->card, "Material card file (JSON; - = stdin)")->required();
  cmd->add_option("--format", args->format, "FE solver: " + export_formats_text())
      ->required()->check(CLI::IsMember(fitlib::card::export_formats()));
  cmd->add_option("--out", args->out, "Keyword file to write (atomically; default or - = stdout)");
  cmd->add_option("--poisson-ratio", args->options.poisson_ratio,
                  "Instantaneous Poisson ratio when the card has no bulk modulus")
      ->capture_default_str()->check(poisson_ratio_range());
  cmd->add_option("--material-id", args->options.material_id, "Material number (ANSYS, LS-DYNA)")
      ->capture_default_str()->check(number_in(1, 999999));  // fits every deck's field
  cmd->add_option("--density", args->options.density_t_per_mm3, "Mass density RO in t/mm3 (LS-DYNA; rubber ~1.2e-9)")
      ->check(number_in(0, 1e-6));  // 1e-6 t/mm3 = 1000 g/cm3: beyond any solid (a negative one was written)
  cmd->add_option("--temperature-c", args->options.temperature_C,
                  "Export at this temperature (degC): times scaled by the card's shift factor, no temperature shift "
                  "in the deck (for laws the solver lacks)")
      ->check(temperature_c_range());
  cmd->add_flag("--allow-extrapolation", args->allow_extrapolation,
                "With --temperature-c: export beyond the card's data window (a warning; without it refused)");
  cmd->add_flag("--allow-inadmissible", args->options.allow_inadmissible,
                "Export a card whose terms break its admissible window or E_inf/E_0 >= 1e-3");
  add_json_flag(cmd, args->json, "the keywords (or, with --out, the file written), on stdout");
  add_verbosity_flags(cmd);
  cmd->callback([args] {
    claim_output("--out", args->out, false);
    const fitlib::card::Card card = fitlib::card::load_card(input_path(args->card));
    std::string text;
    {  // the quality verdict (the deck's header says it too) and, at one temperature, the data window
      const double T = args->options.temperature_C;
      WindowCheck window("export", args->card, card, std::isfinite(T) ? std::vector<double>{T} : std::vector<double>{},
                         args->allow_extrapolation);
      fitlib::model::TestCondition at;
      at.frequency_Hz = std::numeric_limits<double>::quiet_NaN(), at.temperature_C = T;  // the temperature alone
      if (std::isfinite(T)) window.beyond(at);
      text = fitlib::card::export_card(card, args->format, args->options);
    }
    if (!args->json) return emit(args->out, text);
    nlohmann::json j = {{"card", args->card}, {"format", args->format}};
    if (args->out.empty() || args->out == "-") {
      j["keywords"] = text;
    } else {
      emit(args->out, text);
      j["out"] = args->out;
    }
    std::cout << j.dump(2) << "\n";
  });
}

}  // namespace fitcli
