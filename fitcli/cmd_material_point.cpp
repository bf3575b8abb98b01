// fitcli material-point: Report II §7.2 test cases of a Fritzson card at one material point,
// written as stress–strain loops (CSV).
#include "commands.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/model/fritzson_cases.hpp"
#include "output.hpp"

namespace fitcli {

void register_material_point(CLI::App& app) {
  struct Args {
    std::string card, case_id, out;
    int steps_per_cycle = 200;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "material-point", "Run a Report II §7.2 case (7.1–7.5) for a fritzson card; loops as CSV");
  cmd->add_option("--card", args->card, "material card (model fritzson or fritzson-iso)")->required();
  cmd->add_option("--case", args->case_id, "7.1, 7.2, 7.3, 7.4 (cyclic) or 7.5 (ramp)")->required();
  cmd->add_option("--steps-per-cycle", args->steps_per_cycle, "time steps per cycle (default 200)");
  cmd->add_option("--out", args->out, "output CSV (default stdout)");
  cmd->callback([args] {
    using namespace fitlib;
    const auto card = card::load_card(args->card);
    if (card.model_kind != "fritzson" && card.model_kind != "fritzson-iso")
      throw core::UsageError("material-point needs a fritzson card, not '" + card.model_kind + "'");
    const double reference_C = card.model_options.value("reference_C", 23.0);
    const model::fritzson::MaterialPoint point(card.values(), card.model_kind == "fritzson",
                                               reference_C, model::fritzson::Scheme::exponential);
    const auto& c = model::fritzson::thesis_case(args->case_id);
    const auto loops = model::fritzson::run_thesis_case(point, c, args->steps_per_cycle);
    emit(args->out, model::fritzson::case_loops_csv(c, loops));
  });
}

}  // namespace fitcli
