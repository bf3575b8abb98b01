// fitcli material-point: drives the material point of any card through a cyclic strain
// program (model::drive, docs/model.md §"drive") and writes time, strains and stresses (CSV);
// for Fritzson cards --case runs a Report II §7.2 test case instead.
#include <cmath>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/finite_output.hpp"
#include "fitlib/model/fritzson_cases.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/work_caps.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "window_check.hpp"

namespace fitcli {
namespace {

struct Args {
  std::string card, case_id, out, test = "shear", orientation, fidelity = "viscoelastic";
  int steps_per_cycle = 200, cycles = 5;
  double amplitude = 0.01, mean_strain = 0.0, frequency_Hz = 1.0;
  bool allow_extrapolation = false, hold_damage = false;
  double temperature_C = std::numeric_limits<double>::quiet_NaN();
  double bulk_modulus_MPa = std::numeric_limits<double>::quiet_NaN();
  bool json = false;
};

// The CSV, or with --json the same rows as one JSON document; every number checked finite before
// anything is written (NumericalError naming column and row).
void write_table(const Args& a, const std::string& csv) {
  fitlib::core::require_finite_csv(csv, "material-point " + (a.out.empty() ? std::string("output") : a.out));
  if (!a.json) return emit(a.out, csv);
  const nlohmann::json j = {{"card", a.card}, {"case", a.case_id}, {"rows", csv_rows_json(csv)}};
  emit(a.out, j.dump(2) + "\n");
}

std::string drive_csv(const fitlib::model::DriveResult& r) {
  static const char* kVoigt[6] = {"11", "22", "33", "23", "13", "12"};
  std::string out = "time_s";
  for (const char* v : kVoigt) out += std::string(",strain_") + v;
  for (const char* v : kVoigt) out += std::string(",stress_") + v + "_MPa";
  out += "\n";
  for (size_t n = 0; n < r.time_s.size(); ++n) {
    out += exact(r.time_s[n]);
    for (int i = 0; i < 6; ++i) out += "," + exact(r.strain[n][i]);
    for (int i = 0; i < 6; ++i) out += "," + exact(r.stress[n][i]);
    out += "\n";
  }
  return out;
}


// Work caps by cost (fitlib/model/work_caps.hpp, shared with the Python module): exit 3 naming the
// options, before the history is made.
void run_case(const Args& a, const fitlib::card::Card& card) {
  using namespace fitlib;
  const model::fritzson::MaterialPoint point = model::fritzson::thesis_point(*card.model(), card.values());
  const auto& c = model::fritzson::thesis_case(a.case_id);
  model::fritzson::check_thesis_case_work(*card.model(), card.values(), c, a.steps_per_cycle, "--steps-per-cycle");
  write_table(a, model::fritzson::case_loops_csv(c, model::fritzson::run_thesis_case(point, c, a.steps_per_cycle)));
}

void run_cyclic(const Args& a, const fitlib::card::Card& card) {
  using namespace fitlib;
  if (a.fidelity != "viscoelastic" && a.fidelity != "elastic")
    throw core::UsageError("--fidelity must be viscoelastic or elastic, not '" + a.fidelity + "'");
  if (!(a.frequency_Hz > 0.0))  // (the deprecated --frequency has no validator)
    throw core::UsageError("--frequency-hz: must be > 0, got " + core::short_number(a.frequency_Hz));
  model::TestCondition c;
  c.mode = model::parse_test_mode(a.test);
  c.orientation = a.orientation;
  c.temperature_C = a.temperature_C;
  c.frequency_Hz = a.frequency_Hz;
  c.strain_amplitude = a.amplitude;
  WindowCheck("material-point", a.card, card, {a.temperature_C}, a.allow_extrapolation).beyond(c);
  model::PointOptions options;
  options.fidelity = a.fidelity == "elastic" ? core::Fidelity::elastic
                                             : core::Fidelity::complete;
  options.frequency_Hz = a.frequency_Hz;
  options.temperature_C = a.temperature_C;
  options.bulk_modulus_MPa = a.bulk_modulus_MPa;
  if (std::isnan(options.bulk_modulus_MPa)) {  // a card without K: ν = 0.4995, as eval, export and scenes
    model::TestCondition native;
    native.mode = card.model()->native_mode();
    native.frequency_Hz = a.frequency_Hz;
    native.temperature_C = a.temperature_C;
    options.bulk_modulus_MPa =
        card::point_bulk_modulus_MPa(*card.model(), card.values(), native, card::kDefaultPoissonRatio);
    if (!std::isnan(options.bulk_modulus_MPa))
      note("the card has no bulk modulus: K = " + fitlib::core::short_number(options.bulk_modulus_MPa) +
           " MPa from its instantaneous modulus and Poisson ratio " +
           fitlib::core::short_number(card::kDefaultPoissonRatio) + " (as eval and export; --bulk-modulus to choose)");
  }
  if (a.hold_damage) {  // as the segment's complete level (docs/segment.md "Damage held beyond the tested amplitudes")
    options.damage_driver_hold = card::DataWindow(card).damage_drivers();
    if (options.damage_driver_hold.empty())
      throw core::InputError("--hold-damage: the card holds no damage drivers of its tests (fit.data_window.damage_driver: "
                             "a card of a model with damage, fitted to a table with strain amplitudes)",
                             a.card, 0, 0, "fit.data_window.damage_driver");
  }
  const auto point = model::make_material_point(*card.model(), card.values(), options);
  model::check_point_work(model::point_work(point->state_size(), double(a.cycles) * a.steps_per_cycle, c.mode),
                          point->describe(), "--cycles x --steps-per-cycle");
  const auto history = model::fritzson::cyclic_history(a.amplitude, a.mean_strain, a.frequency_Hz,
                                                       a.cycles, a.steps_per_cycle);
  write_table(a, drive_csv(model::drive(*point, model::test_program(c, history))));
}

// Old option names and their replacements.
const std::pair<const char*, const char*> kRenamed[] = {
    {"--test", "--mode"}, {"--frequency", "--frequency-hz"}, {"--temperature", "--temperature-c"}};

}  // namespace

void register_material_point(CLI::App& app) {
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "material-point",
      "Drive a card's material point through a cyclic test (any model; CSV of time, strains, "
      "stresses), or run a Report II §7.2 case (7.1–7.5) of a fritzson card");
  cmd->add_option("--card", args->card, "material card file (JSON; - = stdin)")->required();
  cmd->add_option("--case", args->case_id, "fritzson cards: 7.1, 7.2, 7.3, 7.4 (cyclic) or 7.5 (ramp)");
  cmd->add_option("--mode", args->test, "shear (default), uniaxial or bulk");
  cmd->add_option("--orientation", args->orientation, "11, 22, 33, 12, 13 or 23 (default 12 / 22)");
  cmd->add_option("--amplitude", args->amplitude, "strain amplitude (shear: γ; default 0.01)")
      ->check(strain_amplitude_range());
  cmd->add_flag("--allow-extrapolation", args->allow_extrapolation,
                "Drive beyond the card's data window (a warning; without it such a test is refused)");
  cmd->add_option("--mean-strain", args->mean_strain, "mean strain (default 0); ε(t) = mean − a cos 2πft")
      ->check(mean_strain_range());
  cmd->add_option("--frequency-hz", args->frequency_Hz, "Hz (default 1)")->check(positive_number());
  cmd->add_option("--cycles", args->cycles, "cycles (default 5)")->check(number_in(1, 1e6));
  cmd->add_option("--temperature-c", args->temperature_C, "degC (default: the card's reference)")
      ->check(temperature_c_range());
  // Deprecated spellings (one release): the same names as every other subcommand.
  for (const auto& renamed : kRenamed) {
    const std::string name = renamed.first;
    auto* old = name == "--test"        ? cmd->add_option(name, args->test)
                : name == "--frequency" ? cmd->add_option(name, args->frequency_Hz)
                                        : cmd->add_option(name, args->temperature_C);
    old->group("");  // hidden from --help
  }
  cmd->add_flag("--hold-damage", args->hold_damage,
                "Hold the damage at the drivers the card's tests reached (fit.data_window.damage_driver), as the "
                "segment's complete level does");
  cmd->add_option("--fidelity", args->fidelity, "viscoelastic (default) or elastic (storage moduli at --frequency-hz)");
  cmd->add_option("--bulk-modulus", args->bulk_modulus_MPa, "MPa, for a linear card without K (default: from its instantaneous modulus and Poisson ratio 0.4995)")
      ->check(positive_number());
  cmd->add_option("--steps-per-cycle", args->steps_per_cycle, "time steps per cycle (default 200)")
      ->check(number_in(4, 1e6));
  cmd->add_option("--out", args->out, "CSV file to write (JSON with --json; default or - = stdout)");
  add_json_flag(cmd, args->json, "the rows instead of CSV, on stdout or in --out");
  add_verbosity_flags(cmd);
  cmd->callback([args, cmd] {
    for (const auto& [old_name, new_name] : kRenamed)
      if (cmd->count(old_name) > 0)
        note(std::string("material-point ") + old_name + " is deprecated: use " + new_name + " (docs/cli.md)");
    claim_output("--out", args->out, false);
    const auto card = fitlib::card::load_card(input_path(args->card));
    if (!args->case_id.empty()) run_case(*args, card);
    else run_cyclic(*args, card);
  });
}

}  // namespace fitcli
