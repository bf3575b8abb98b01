// fitcli synth: a virtual dynamic test — a card evaluated on a test design with seeded noise,
// written as a dynamic-test table. Used to make datasets of known ground truth.
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/data/table.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "window_check.hpp"

namespace fitcli {
namespace {

struct SynthArgs {
  std::string card, mode = "shear", orientation, out, name;
  std::vector<double> frequency_Hz, temperature_C, amplitude;
  bool allow_extrapolation = false;
  double noise = 0.0;
  int specimens = 1;
  std::uint64_t seed = 1;
  bool json = false;
};

void run_synth(const SynthArgs& a) {
  using namespace fitlib;
  claim_output("--out", a.out, a.json);
  const auto card = card::load_card(input_path(a.card));
  const auto model = card.model();
  const auto p = card.values();
  core::Rng rng(a.seed);
  data::DynamicTestTable table;
  const std::vector<double> temperatures =
      a.temperature_C.empty() ? std::vector<double>{std::nan("")} : a.temperature_C;
  const std::vector<double> amplitudes = a.amplitude.empty() ? std::vector<double>{0.0} : a.amplitude;
  WindowCheck window("synth", a.card, card, temperatures, a.allow_extrapolation);
  for (double T : temperatures)
    for (double amp : amplitudes)
      for (double f : a.frequency_Hz)
        for (int s = 1; s <= a.specimens; ++s) {
          data::DynamicTestRow row;
          row.condition.mode = model::parse_test_mode(a.mode);
          row.condition.orientation = a.orientation;
          row.condition.frequency_Hz = f;
          row.condition.temperature_C = T;
          row.condition.strain_amplitude = amp;
          window.beyond(row.condition);
          const auto m = model->moduli(p.data(), row.condition);
          // Multiplicative Gaussian scatter, independent for storage and loss.
          row.storage_MPa = m.storage * (1.0 + a.noise * rng.normal());
          row.loss_MPa = m.loss * (1.0 + a.noise * rng.normal());
          row.material = a.name.empty() ? card.name : a.name;
          row.specimen = std::to_string(s);
          table.rows.push_back(row);
        }
  emit_with(a.out, [&](const std::string& path) { data::write_dynamic_table(path, table); });
  if (a.json)
    std::cout << nlohmann::json{{"card", a.card}, {"out", a.out}, {"rows", table.rows.size()}, {"seed", a.seed},
                                {"noise", a.noise}}.dump(2)
              << "\n";
  else
    detail("wrote " + std::to_string(table.rows.size()) + " rows to " + a.out);
}

}  // namespace

void register_synth(CLI::App& app) {
  auto a = std::make_shared<SynthArgs>();
  auto* cmd = app.add_subcommand("synth", "Virtual dynamic test: evaluate a card on a test design with seeded noise");
  cmd->add_option("--card", a->card, "Material card file (JSON; - = stdin) holding the true parameters")->required();
  cmd->add_option("--mode", a->mode, "shear | uniaxial | bulk")->capture_default_str();
  cmd->add_option("--orientation", a->orientation, "Thesis orientation label");
  cmd->add_option("--frequency-hz", a->frequency_Hz, "Frequencies, Hz")->required()->delimiter(',')
      ->check(positive_number());
  cmd->add_option("--temperature-c", a->temperature_C, "Temperatures, degC")->delimiter(',')->check(temperature_c_range());
  cmd->add_option("--amplitude", a->amplitude, "Strain amplitudes")->delimiter(',')->check(strain_amplitude_range());
  cmd->add_flag("--allow-extrapolation", a->allow_extrapolation,
                "Evaluate beyond the card's data window (a warning; without it such a design is refused)");
  cmd->add_option("--noise", a->noise, "Relative standard deviation of the scatter (0.01 = 1 %)")
      ->capture_default_str()->check(number_in(0.0, 0.5));
  cmd->add_option("--specimens", a->specimens, "Specimens per test point")->capture_default_str()
      ->check(CLI::Range(1, 100));
  cmd->add_option("--seed", a->seed, "Random seed")->capture_default_str();
  cmd->add_option("--name", a->name, "Material label of the rows (default: the card's name)");
  // Deprecated spelling (one release): the label option is --name in every subcommand.
  cmd->add_option("--material", a->name)->group("");
  cmd->add_option("--out", a->out, "Table file to write (native CSV, atomically; - = stdout)")->required();
  add_json_flag(cmd, a->json, "what was written, on stdout");
  add_verbosity_flags(cmd);
  cmd->callback([a, cmd] {
    if (cmd->count("--material") > 0) note("synth --material is deprecated: use --name (docs/cli.md)");
    run_synth(*a);
  });
}

}  // namespace fitcli
