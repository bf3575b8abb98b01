// fitcli: command-line front of fitlib (formats.md §6).
#include <iostream>

#include "commands.hpp"
#include "fitlib/core/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fitcli: fit material models to dynamic tests, write cards, run belt scenes"};
  app.require_subcommand(1);
  app.set_version_flag("--version", FITLIB_VERSION);
  fitcli::register_fit(app);
  fitcli::register_eval(app);
  fitcli::register_export(app);
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
