// fitcli: command-line front of fitlib (docs/cli.md).
#include <iostream>

#include "commands.hpp"
#include "fitlib/core/error.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "version_info.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fitcli: fit material models to dynamic tests, write cards, run belt scenes (docs/cli.md)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", fitcli::version_text());
  fitcli::add_verbosity_flags(&app);
  fitcli::register_fit(app);
  fitcli::register_eval(app);
  fitcli::register_export(app);
  fitcli::register_synth(app);
  fitcli::register_waveform(app);
  fitcli::register_surface(app);
  fitcli::register_belt(app);
  fitcli::register_accumulate(app);
  fitcli::register_material_point(app);
  fitcli::register_plot(app);
  fitcli::register_segment(app);
  fitcli::register_life(app);
  fitcli::register_life_fit(app);
  fitcli::register_sweep(app);
  fitcli::register_visco_card(app);
  fitcli::require_finite_numbers(app);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "fitcli: error: " + std::string(e.what()) + " (--help lists the options)\n";
  });
  fitcli::set_command_line(argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : fitlib::core::kUsageError;
  } catch (const std::exception& e) {
    std::cerr << "fitcli: error: " << fitcli::with_stdin_named(e.what()) << "\n";
    return fitlib::core::exit_code_for(e);
  }
  return 0;
}
