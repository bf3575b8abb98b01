#pragma once
// fitcli is a thin front: each subcommand parses its arguments, calls fitlib and prints.
// A subcommand registers itself on the app; errors are thrown and mapped to exit codes in main.
#include <CLI/CLI.hpp>

namespace fitcli {

void register_fit(CLI::App& app);
void register_eval(CLI::App& app);
void register_export(CLI::App& app);
void register_synth(CLI::App& app);
void register_waveform(CLI::App& app);
void register_surface(CLI::App& app);
void register_belt(CLI::App& app);
void register_accumulate(CLI::App& app);
void register_material_point(CLI::App& app);
void register_plot(CLI::App& app);
void register_segment(CLI::App& app);
void register_life(CLI::App& app);
void register_life_fit(CLI::App& app);
void register_sweep(CLI::App& app);
void register_visco_card(CLI::App& app);

// The export formats with their Prony term limits, for help texts (cmd_export.cpp).
std::string export_formats_text();

}  // namespace fitcli
