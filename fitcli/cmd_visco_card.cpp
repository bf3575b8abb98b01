// fitcli visco-card: a hyperelastic card (long-term response) and a shear Prony card → the
// visco-hyperelastic card (docs/hyperelastic.md §"Visco-hyperelastic").
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "fitlib/card/hyperelastic.hpp"
#include "inputs.hpp"
#include "output.hpp"

namespace fitcli {

void register_visco_card(CLI::App& app) {
  struct Args {
    std::string base, prony, out, name = "visco-hyperelastic";
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("visco-card",
                                 "Combine a hyperelastic card and a shear Prony card into a visco-hyperelastic card");
  cmd->add_option("--base", a->base, "Hyperelastic card (its long-term response; JSON)")->required();
  cmd->add_option("--prony", a->prony, "Shear card with an exact Prony series (prony, zener3, ...; JSON)")->required();
  cmd->add_option("--out", a->out, "Card file to write (atomically; - = stdout)");
  cmd->add_option("--name", a->name, "Material name in the card")->capture_default_str();
  add_json_flag(cmd, a->json, "the card, on stdout");
  add_verbosity_flags(cmd);
  cmd->callback([a] {
    claim_output("--out", a->out, a->json);
    const auto base = fitlib::card::load_card(input_path(a->base));
    const auto prony = fitlib::card::load_card(input_path(a->prony));
    const auto card = fitlib::card::visco_hyperelastic_card(base, prony, a->name);
    if (!a->out.empty()) emit_with(a->out, [&](const std::string& path) { fitlib::card::save_card(path, card); });
    for (const auto& w : card.fit["quality"]["warnings"]) warning(w.get<std::string>());
    if (a->json) std::cout << fitlib::card::card_to_json(card).dump(2) << "\n";
  });
}

}  // namespace fitcli
