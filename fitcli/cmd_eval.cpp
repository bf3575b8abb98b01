// fitcli eval: a card's moduli over a grid of test conditions (docs/formats.md §6).
#include <iostream>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "output.hpp"

namespace fitcli {
namespace {

struct EvalArgs {
  std::string card, mode = "shear", orientation, out;
  std::vector<double> frequency_Hz, temperature_C, amplitude, time_s;
  bool json = false;
};

// --time-s: relaxation modulus M(t) after a unit strain step and creep compliance J(t) after a
// unit stress step; a model that has no creep compliance (fritzson) leaves J empty and says why.
void run_eval_time(const EvalArgs& a) {
  using namespace fitlib;
  const auto card = card::load_card(a.card);
  const auto model = card.model();
  const auto p = card.values();
  const std::vector<double> temperatures =
      a.temperature_C.empty() ? std::vector<double>{std::nan("")} : a.temperature_C;
  std::ostringstream csv;
  nlohmann::json rows = nlohmann::json::array();
  csv << "mode,temperature_C,time_s,relaxation_modulus_MPa,creep_compliance_per_MPa\n";
  std::string refused;
  for (double T : temperatures)
    for (double t : a.time_s) {
      model::TestCondition c;
      c.mode = model::parse_test_mode(a.mode);
      c.orientation = a.orientation;
      c.temperature_C = T;
      const double m = model->relaxation_modulus(p.data(), c, t);
      std::optional<double> j;
      try {
        j = model->creep_compliance(p.data(), c, t);
      } catch (const core::UsageError& e) {
        refused = e.what();
      }
      csv << a.mode << "," << (std::isnan(T) ? "" : exact(T)) << "," << exact(t) << "," << exact(m) << ","
          << (j ? exact(*j) : "") << "\n";
      rows.push_back({{"time_s", t},
                      {"temperature_C", std::isnan(T) ? nlohmann::json(nullptr) : nlohmann::json(T)},
                      {"relaxation_modulus_MPa", m},
                      {"creep_compliance_per_MPa", j ? nlohmann::json(*j) : nlohmann::json(nullptr)}});
    }
  if (!refused.empty()) std::cerr << "fitcli: note: no creep compliance: " << refused << "\n";
  if (a.json)
    emit(a.out, nlohmann::json{{"card", a.card}, {"mode", a.mode}, {"rows", rows}}.dump(2) + "\n");
  else
    emit(a.out, csv.str());
}

void run_eval(const EvalArgs& a) {
  using namespace fitlib;
  if (a.frequency_Hz.empty() == a.time_s.empty())
    throw core::UsageError("eval: give --frequency-hz (complex moduli) or --time-s (relaxation, creep), one of them");
  if (!a.time_s.empty()) return run_eval_time(a);
  const auto card = card::load_card(a.card);
  const auto model = card.model();
  const auto p = card.values();
  const auto mode = model::parse_test_mode(a.mode);
  const std::vector<double> temperatures =
      a.temperature_C.empty() ? std::vector<double>{std::nan("")} : a.temperature_C;
  const std::vector<double> amplitudes = a.amplitude.empty() ? std::vector<double>{0.0} : a.amplitude;
  std::ostringstream csv;
  nlohmann::json rows = nlohmann::json::array();
  csv << "mode,orientation,frequency_Hz,temperature_C,strain_amplitude,storage_MPa,loss_MPa,tan_delta,"
         "mean_modulus_MPa\n";
  for (double T : temperatures)
    for (double amp : amplitudes)
      for (double f : a.frequency_Hz) {
        model::TestCondition c;
        c.mode = mode;
        c.orientation = a.orientation;
        c.frequency_Hz = f;
        c.temperature_C = T;
        c.strain_amplitude = amp;
        auto m = model->moduli(p.data(), c);
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
                        {"mean_modulus_MPa", m.mean}});
      }
  if (a.json)
    emit(a.out, nlohmann::json{{"card", a.card}, {"mode", a.mode}, {"orientation", a.orientation}, {"rows", rows}}
                        .dump(2) + "\n");
  else
    emit(a.out, csv.str());
}

}  // namespace

void register_eval(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  auto* cmd = app.add_subcommand("eval", "Evaluate a card: storage, loss, tan delta and mean modulus (MPa), or M(t) and J(t)");
  cmd->add_option("--card", args->card, "Material card (JSON)")->required();
  cmd->add_option("--mode", args->mode, "shear | uniaxial | bulk")->capture_default_str();
  cmd->add_option("--orientation", args->orientation, "Thesis orientation label (11, 22, 33, 12, 13, 23)");
  cmd->add_option("--frequency-hz", args->frequency_Hz, "Frequencies in Hz, comma separated")
      ->delimiter(',')->check(CLI::PositiveNumber);
  cmd->add_option("--time-s", args->time_s,
                  "Times in s, comma separated: relaxation modulus M(t) and creep compliance J(t) instead")
      ->delimiter(',')->check(CLI::PositiveNumber);
  cmd->add_option("--temperature-c", args->temperature_C, "Temperatures in degC (default: reference)")
      ->delimiter(',');
  cmd->add_option("--amplitude", args->amplitude, "Strain amplitudes (default: small-amplitude limit)")
      ->delimiter(',')->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", args->out, "Output file (default stdout); written atomically");
  cmd->add_flag("--json", args->json, "Print one JSON document instead of CSV");
  cmd->callback([args] { run_eval(*args); });
}

}  // namespace fitcli
