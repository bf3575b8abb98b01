// fitcli eval: a card's moduli over a grid of test conditions (docs/cli.md "eval"). The mode is
// the card's own unless --mode asks for another (converted as export does, card/conversion.hpp);
// conditions beyond the card's data window are refused unless --allow-extrapolation.
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/card/data_window.hpp"
#include "fitlib/card/export.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/model/hyperelastic.hpp"
#include "hyperelastic.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "window_check.hpp"

namespace fitcli {
namespace {

struct EvalArgs {
  std::string card, mode, orientation, out, plot, data_format = "native";
  std::vector<std::string> data;  // --plot: tables to plot against
  std::vector<double> frequency_Hz, temperature_C, amplitude, time_s;
  std::vector<double> stretch;  // hyperelastic cards (hyperelastic.hpp)
  double poisson_ratio = fitlib::card::ExportOptions{}.poisson_ratio;
  bool json = false, allow_extrapolation = false;
};

// --time-s: relaxation modulus M(t) after a unit strain step and creep compliance J(t) after a
// unit stress step; a model that has no creep compliance (fritzson) leaves J empty and says why.
void run_eval_time(const EvalArgs& a, const fitlib::card::Card& card, fitlib::model::TestMode mode) {
  using namespace fitlib;
  const auto model = card.model();
  const auto p = card.values();
  const std::vector<double> temperatures =
      a.temperature_C.empty() ? std::vector<double>{std::nan("")} : a.temperature_C;
  std::ostringstream csv;
  nlohmann::json rows = nlohmann::json::array();
  csv << "mode,temperature_C,time_s,relaxation_modulus_MPa,creep_compliance_per_MPa\n";
  std::string refused;
  WindowCheck window("eval", a.card, card, a.temperature_C, a.allow_extrapolation);
  for (double T : temperatures)
    for (double t : a.time_s) {
      model::TestCondition c;
      c.mode = mode;
      c.orientation = a.orientation;
      c.temperature_C = T;
      const bool extrapolated = window.beyond(c);
      const double m = model->relaxation_modulus(p.data(), c, t);
      std::optional<double> j;
      try {
        j = model->creep_compliance(p.data(), c, t);
      } catch (const core::UsageError& e) {
        refused = e.what();
      }
      csv << model::to_string(mode) << "," << (std::isnan(T) ? "" : exact(T)) << "," << exact(t) << "," << exact(m)
          << "," << (j ? exact(*j) : "") << "\n";
      rows.push_back({{"time_s", t},
                      {"temperature_C", std::isnan(T) ? nlohmann::json(nullptr) : nlohmann::json(T)},
                      {"relaxation_modulus_MPa", m},
                      {"creep_compliance_per_MPa", j ? nlohmann::json(*j) : nlohmann::json(nullptr)},
                      {"extrapolated", extrapolated}});
    }
  if (!refused.empty()) note("no creep compliance: " + refused);
  if (a.json)
    emit(a.out, nlohmann::json{{"card", a.card}, {"mode", model::to_string(mode)}, {"rows", rows}}.dump(2) + "\n");
  else
    emit(a.out, csv.str());
}

void run_eval_frequency(const EvalArgs& a, const fitlib::card::Card& card, fitlib::model::TestMode mode) {
  using namespace fitlib;
  const auto model = card.model();
  const auto p = card.values();
  const std::vector<double> temperatures =
      a.temperature_C.empty() ? std::vector<double>{std::nan("")} : a.temperature_C;
  const std::vector<double> amplitudes = a.amplitude.empty() ? std::vector<double>{0.0} : a.amplitude;
  std::ostringstream csv;
  nlohmann::json rows = nlohmann::json::array();
  csv << "mode,orientation,frequency_Hz,temperature_C,strain_amplitude,storage_MPa,loss_MPa,tan_delta,"
         "mean_modulus_MPa\n";
  WindowCheck window("eval", a.card, card, a.temperature_C, a.allow_extrapolation);
  for (double T : temperatures)
    for (double amp : amplitudes)
      for (double f : a.frequency_Hz) {
        model::TestCondition c;
        c.mode = mode;
        c.orientation = a.orientation;
        c.frequency_Hz = f;
        c.temperature_C = T;
        c.strain_amplitude = amp;
        const bool extrapolated = window.beyond(c);
        auto m = card::moduli_in_mode(*model, p, c, a.poisson_ratio);
        const std::string at = " at " + exact(f) + " Hz" + (std::isnan(T) ? "" : ", " + exact(T) + " degC");
        m.storage = core::require_finite(m.storage, "storage modulus" + at);
        m.loss = core::require_finite(m.loss, "loss modulus" + at);
        m.mean = core::require_finite(m.mean, "mean modulus" + at);
        const double tan_delta = core::require_finite(m.loss / m.storage, "tan delta" + at);
        csv << model::to_string(mode) << "," << a.orientation << "," << exact(f) << ","
            << (std::isnan(T) ? "" : exact(T)) << "," << exact(amp) << "," << exact(m.storage) << ","
            << exact(m.loss) << "," << exact(tan_delta) << "," << exact(m.mean) << "\n";
        rows.push_back({{"frequency_Hz", f},
                        {"temperature_C", std::isnan(T) ? nlohmann::json(nullptr) : nlohmann::json(T)},
                        {"strain_amplitude", amp},
                        {"storage_MPa", m.storage},
                        {"loss_MPa", m.loss},
                        {"tan_delta", tan_delta},
                        {"mean_modulus_MPa", m.mean},
                        {"extrapolated", extrapolated}});
      }
  if (a.json)
    emit(a.out, nlohmann::json{{"card", a.card}, {"mode", model::to_string(mode)}, {"orientation", a.orientation},
                               {"rows", rows}}.dump(2) + "\n");
  else
    emit(a.out, csv.str());
}

// A hyperelastic card: stresses over --stretch in --mode; the dynamic options do not apply.
void run_eval_hyperelastic(const EvalArgs& a) {
  if (!a.frequency_Hz.empty() || !a.time_s.empty() || !a.temperature_C.empty() || !a.amplitude.empty() ||
      !a.plot.empty())
    throw fitlib::core::UsageError("eval of a hyperelastic card takes --mode and --stretch (plot it with fitcli plot)");
  claim_output("--out", a.out, false);
  const auto card = fitlib::card::load_card(input_path(a.card));
  if (!card.model()->hyperelastic())
    throw fitlib::core::UsageError("--stretch: card '" + a.card + "' (model " + card.model_kind +
                                   ") is not hyperelastic; evaluate it with --frequency-hz or --time-s");
  run_hyperelastic_eval(card, a.card, a.mode, a.stretch, a.out, a.json);
}

void run_eval(const EvalArgs& a) {
  using namespace fitlib;
  if (!a.stretch.empty()) return run_eval_hyperelastic(a);
  if (a.frequency_Hz.empty() == a.time_s.empty())
    throw core::UsageError("eval: give --frequency-hz (complex moduli) or --time-s (relaxation, creep), one of them");
  if (!a.plot.empty() && a.data.empty()) throw core::UsageError("eval --plot needs --data (the table to plot against)");
  claim_output("--out", a.out, false);  // with --json the rows are JSON wherever they go
  if (!a.plot.empty()) claim_png("--plot", a.plot);
  const auto card = card::load_card(input_path(a.card));
  const auto data = input_paths(a.data);
  const auto mode = a.mode.empty() ? card.model()->native_mode() : model::parse_test_mode(a.mode);
  if (!a.time_s.empty()) run_eval_time(a, card, mode);
  else run_eval_frequency(a, card, mode);
  if (!a.plot.empty()) draw_figure(a.plot, [&] { plot_card(card, data, a.data_format, "", a.plot); });
}

}  // namespace

void register_eval(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  auto* cmd = app.add_subcommand("eval", "Evaluate a card: storage, loss, tan delta and mean modulus (MPa), or M(t) and J(t)");
  cmd->add_option("--card", args->card, "Material card file (JSON; - = stdin)")->required();
  cmd->add_option("--mode", args->mode, "shear | uniaxial | bulk (default: the card's own mode)");
  cmd->add_option("--poisson-ratio", args->poisson_ratio,
                  "Another --mode of a card without a bulk modulus: instantaneous Poisson ratio (as export)")
      ->capture_default_str()->check(poisson_ratio_range());
  cmd->add_option("--orientation", args->orientation, "Thesis orientation label (11, 22, 33, 12, 13, 23)");
  cmd->add_option("--frequency-hz", args->frequency_Hz, "Frequencies in Hz, comma separated")
      ->delimiter(',')->check(positive_number());
  cmd->add_option("--stretch", args->stretch,
                  "Hyperelastic cards: stretches (simple_shear: shear strains, volumetric: volume ratios), comma "
                  "separated; --mode uniaxial (default) | equibiaxial | planar | simple_shear | volumetric")
      ->delimiter(',');
  cmd->add_option("--time-s", args->time_s,
                  "Times in s, comma separated: relaxation modulus M(t) and creep compliance J(t) instead")
      ->delimiter(',')->check(positive_number());
  cmd->add_option("--temperature-c", args->temperature_C, "Temperatures in degC (default: reference)")
      ->delimiter(',')->check(temperature_c_range());
  cmd->add_option("--amplitude", args->amplitude, "Strain amplitudes (default: small-amplitude limit)")
      ->delimiter(',')->check(strain_amplitude_range());
  cmd->add_flag("--allow-extrapolation", args->allow_extrapolation,
                "Evaluate beyond the card's data window (a warning, and extrapolated: true in --json)");
  cmd->add_option("--out", args->out, "Output file (CSV, or JSON with --json; default or - = stdout)");
  cmd->add_option("--plot", args->plot, "Also write the figure of fitcli plot (PNG file) of --data against the card");
  cmd->add_option("--data", args->data, "With --plot: the data file(s) to plot against the card");
  cmd->add_option("--format", args->data_format, "With --plot: format of --data (native | pyvisco | eplexor)")
      ->capture_default_str()->check(CLI::IsMember({"native", "pyvisco", "eplexor"}));
  add_json_flag(cmd, args->json, "the rows instead of CSV, on stdout or in --out");
  add_verbosity_flags(cmd);
  cmd->callback([args] { run_eval(*args); });
}

}  // namespace fitcli
