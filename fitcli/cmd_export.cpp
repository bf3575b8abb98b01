// fitcli export: FE-solver material keywords from a card (docs/formats.md §3).
#include <memory>

#include "commands.hpp"
#include "fitlib/card/export.hpp"
#include "output.hpp"

namespace fitcli {

void register_export(CLI::App& app) {
  struct Args {
    std::string card, format, out;
    fitlib::card::ExportOptions options;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("export", "Write a card as Abaqus, ANSYS or LS-DYNA material keywords");
  cmd->add_option("--card", args->card, "Material card (JSON)")->required();
  cmd->add_option("--format", args->format, "abaqus | ansys | lsdyna | calculix")
      ->required()->check(CLI::IsMember({"abaqus", "ansys", "lsdyna", "calculix"}));
  cmd->add_option("--out", args->out, "Output file (default stdout); written atomically");
  cmd->add_option("--poisson-ratio", args->options.poisson_ratio,
                  "Instantaneous Poisson ratio when the card has no bulk modulus")
      ->capture_default_str()->check(CLI::Range(0.0, 0.49999999));
  cmd->add_option("--material-id", args->options.material_id, "Material number (ANSYS, LS-DYNA)")
      ->capture_default_str();
  cmd->add_option("--density", args->options.density_t_per_mm3, "Mass density RO in t/mm3 (LS-DYNA; rubber ~1.2e-9)");
  cmd->add_flag("--allow-inadmissible", args->options.allow_inadmissible,
                "Export a card whose terms break its admissible window or E_inf/E_0 >= 1e-3");
  cmd->callback([args] {
    emit(args->out, fitlib::card::export_card(fitlib::card::load_card(args->card), args->format, args->options));
  });
}

}  // namespace fitcli
