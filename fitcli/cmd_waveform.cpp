// fitcli waveform: raw force/displacement (or stress/strain) signals → one dynamic-test row per
// signal file, in argument order (docs/cli.md "waveform").
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/data/csv.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/data/waveform.hpp"
#include "inputs.hpp"
#include "output.hpp"

namespace fitcli {
namespace {

struct WaveformArgs {
  std::vector<std::string> signals;
  std::string specimen, out;
  bool json = false;
  fitlib::data::WaveformOptions options;
};

nlohmann::json nullable(double value, bool valid = true) {
  return valid && !std::isnan(value) ? nlohmann::json(value) : nullptr;
}

nlohmann::json report_json(const WaveformArgs& args, const std::string& signals, const fitlib::data::WaveformRecord& record,
                           const fitlib::data::WaveformReport& report,
                           const fitlib::data::DynamicTestRow& row) {
  const auto& s = record.specimen;
  nlohmann::json periods = nlohmann::json::array();
  for (const auto& p : report.periods)
    periods.push_back({{"start_s", p.start_s},
                       {"samples", p.samples},
                       {"storage_MPa", p.storage_MPa},
                       {"loss_MPa", p.loss_MPa},
                       {"loss_angle_deg", p.loss_angle_rad * 180.0 / fitlib::core::kPi},
                       {"stress_amplitude_MPa", p.stress_amplitude_MPa},
                       {"strain_amplitude", p.strain_amplitude},
                       {"mean_stress_MPa", p.mean_stress_MPa},
                       {"mean_strain", p.mean_strain},
                       {"loss_energy_MPa", p.loss_energy_MPa},
                       {"circle_deviation", p.circle_deviation},
                       {"fit_residual", p.fit_residual}});
  return {
      {"schema", "fitlib.waveform/1"},
      {"source", {{"signals", signals},
                  {"sha256", record.source_sha256},
                  {"specimen_file", args.specimen.empty() ? nlohmann::json(nullptr) : nlohmann::json(args.specimen)}}},
      {"specimen", {{"mode", fitlib::model::to_string(s.mode)},
                    {"area_mm2", nullable(s.area_mm2)},
                    {"thickness_mm", nullable(s.thickness_mm)},
                    {"length_mm", nullable(s.length_mm)},
                    {"volume_mm3", nullable(s.volume_mm3)},
                    {"n_specimens", s.n_specimens},
                    {"temperature_C", nullable(s.temperature_C)},
                    {"material", s.material},
                    {"specimen", s.specimen},
                    {"orientation", s.orientation}}},
      {"analysis", {{"frequency_Hz", report.frequency_Hz},
                    {"samples_per_period", report.samples_per_period},
                    {"smoothing_window", report.smoothing_window},
                    {"harmonics", report.harmonics},
                    {"periods", periods}}},
      {"result", {{"storage_MPa", report.storage_MPa},
                  {"loss_MPa", report.loss_MPa},
                  {"tan_delta", report.tan_delta},
                  {"loss_angle_deg", report.loss_angle_deg},
                  {"storage_std_MPa", report.storage_std_MPa},
                  {"loss_std_MPa", report.loss_std_MPa},
                  {"loss_angle_std_deg", report.loss_angle_std_deg},
                  {"stress_amplitude_MPa", report.stress_amplitude_MPa},
                  {"strain_amplitude", report.strain_amplitude},
                  {"mean_stress_MPa", report.mean_stress_MPa},
                  {"mean_strain", report.mean_strain},
                  {"mean_modulus_MPa", nullable(report.mean_modulus_MPa, report.has_mean_modulus)},
                  {"loss_energy_MPa", report.loss_energy_MPa},
                  {"max_circle_deviation", report.max_circle_deviation},
                  {"max_fit_residual", report.max_fit_residual}}},
      {"row", {{"mode", fitlib::model::to_string(row.condition.mode)},
               {"frequency_Hz", row.condition.frequency_Hz},
               {"storage_MPa", row.storage_MPa},
               {"loss_MPa", row.loss_MPa}}},
      {"out", args.out.empty() ? nlohmann::json(nullptr) : nlohmann::json(args.out)},
      {"warnings", report.warnings}};
}

void print_text(const fitlib::data::WaveformRecord& record, const fitlib::data::WaveformReport& report) {
  const char* modulus = record.specimen.mode == fitlib::model::TestMode::shear ? "G" : "E";
  summary() << std::setprecision(6) << "frequency        " << report.frequency_Hz << " Hz ("
            << report.periods.size() << " periods, " << report.samples_per_period
            << " samples/period, smoothing " << report.smoothing_window << ")\n"
            << "storage " << modulus << "'       " << report.storage_MPa << " MPa (std "
            << report.storage_std_MPa << ")\n"
            << "loss " << modulus << "''         " << report.loss_MPa << " MPa (std "
            << report.loss_std_MPa << ")\n"
            << "loss angle       " << report.loss_angle_deg << " deg (tan delta "
            << report.tan_delta << ")\n"
            << "strain amplitude " << report.strain_amplitude << ", mean " << report.mean_strain
            << "\nstress amplitude " << report.stress_amplitude_MPa << " MPa, mean "
            << report.mean_stress_MPa << " MPa\n";
  if (report.has_mean_modulus) summary() << "mean modulus     " << report.mean_modulus_MPa << " MPa\n";
  summary() << "circle check     " << report.max_circle_deviation << " (max relative radial deviation)\n";
}

void run(const WaveformArgs& args) {
  claim_output("--out", args.out, args.json);
  const std::string sidecar = input_path(args.specimen);
  fitlib::data::DynamicTestTable table;
  nlohmann::json records = nlohmann::json::array();
  for (const auto& given : args.signals) {
    const std::string path = input_path(given);
    const auto record = fitlib::data::read_waveform(path, sidecar);
    const auto report = fitlib::data::analyse_record(record, args.options);
    auto row = fitlib::data::waveform_row(report, record.specimen, record.source_file);
    if (row.specimen.empty()) row.specimen = given;  // each row names its file
    table.rows.push_back(row);
    if (args.json) records.push_back(report_json(args, with_stdin_named(record.source_file), record, report, row));
    if (!args.json && args.signals.size() > 1) summary() << "signals          " << given << "\n";
    if (!args.json) print_text(record, report);
    for (const auto& w : report.warnings) warning(given + ": " + w);
  }
  if (!args.out.empty())
    emit_with(args.out, [&](const std::string& file) { fitlib::data::write_dynamic_table(file, table); });
  if (args.json) {
    // One file: its record; several: the records in argument order.
    const auto doc = records.size() == 1 ? records.front()
                                         : nlohmann::json{{"schema", "fitlib.waveforms/1"}, {"records", records}};
    std::cout << doc.dump(2) << "\n";
  } else if (!args.out.empty()) {
    detail("wrote " + args.out);
  }
}

}  // namespace

void register_waveform(CLI::App& app) {
  auto args = std::make_shared<WaveformArgs>();
  CLI::App* cmd = app.add_subcommand(
      "waveform", "Analyse force/displacement or stress/strain signals (energy method) into a "
                  "dynamic-test table row");
  cmd->add_option("--signals", args->signals, "signal CSV file(s) (time_s, force_N, displacement_mm or "
                                              "stress_MPa, strain; '# key = value' metadata; - = stdin)")
      ->required();
  cmd->add_option("--specimen", args->specimen, "specimen metadata file (JSON sidecar), for every signal file");
  cmd->add_option("--out", args->out, "table file to write: one dynamic-test row per signal file (CSV; - = stdout)");
  add_json_flag(cmd, args->json, "the analysis on stdout (one file: its record; several: fitlib.waveforms/1)");
  add_verbosity_flags(cmd);
  cmd->add_option("--periods", args->options.periods, "whole periods analysed (default 4)");
  cmd->add_option("--smoothing", args->options.smoothing_window,
                  "moving-average width in samples, odd; 0 = automatic (~period/40), 1 = off");
  cmd->add_option("--harmonics", args->options.harmonics,
                  "degree of the per-period trigonometric fit (default 10)");
  cmd->add_option("--frequency-hz", args->options.known_frequency_Hz,
                  "known drive frequency (default: from the signal)")
      ->check(positive_number());
  cmd->callback([args] { run(*args); });
}

}  // namespace fitcli
