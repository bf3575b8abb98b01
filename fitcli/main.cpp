// fitcli: command-line front of fitlib (docs/formats.md §6).
#include <iostream>

#include "commands.hpp"
#include "output.hpp"
#include "fitlib/core/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fitcli: fit material models to dynamic tests, write cards, run belt scenes"};
  app.require_subcommand(1);
  app.set_version_flag("--version", FITLIB_VERSION);
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
  fitcli::register_sweep(app);
  fitcli::set_command_line(argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : fitlib::core::kUsageError;
  } catch (const std::exception& e) {
    std::cerr << "fitcli: error: " << e.what() << "\n";
    return fitlib::core::exit_code_for(e);
  }
  return 0;
}
