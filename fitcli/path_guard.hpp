#pragma once
// Outputs that would replace an input, or one another, are refused before any work: `fit --data
// d.csv --out d.csv` replaced the table it read, `life-fit --out X --peaks-out X` lost one of its
// two files (docs/cli.md "Conventions", docs/reliability.md).
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "fitlib/scene/scene.hpp"

namespace fitcli {

// Checks the file options of the subcommand(s) `app` parsed: every output file (--out, --plot,
// --vtk, --surface-out, --shifts-out, --peaks-out) against every input file (--data, --card,
// --scene, --sweep, --shifts, ...) and against the other outputs, by inode and resolved path
// (core::same_file). UsageError naming both options and the file; also for one input file given
// twice to one option (its rows would count twice).
void refuse_colliding_paths(const CLI::App& app);

// The cards a scene names are inputs too (`life --scene s.toml --plot card.json` replaced the
// scene's bottom card): the subcommands that read a scene check their outputs with
// fitlib::scene::refuse_outputs_on_inputs (scene/output_paths.hpp).

// `belt` and `life` write several files into --out-dir DIR (scene::folder_outputs): the folder and
// each of its files against the scene file and its cards, each of `outputs` (--plot) against the
// folder's files (UsageError, exit 2), then the folder checked writable (InputError, exit 3). Before
// any work and before the folder is made.
void refuse_out_dir_collisions(const fitlib::scene::Scene& scene, const std::string& dir,
                               const std::vector<std::pair<std::string, std::string>>& outputs);

}  // namespace fitcli
