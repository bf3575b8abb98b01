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

// The cards a scene names ([belt.materials] roles, [life] card) are inputs too: `life --scene
// s.toml --plot card.json` replaced the scene's bottom card with the figure. Each output (option,
// path; empty and "-" skipped) against them: UsageError naming the option, the scene key and the
// file, before any work.
void refuse_outputs_on_scene_cards(const fitlib::scene::Scene& scene,
                                   const std::vector<std::pair<std::string, std::string>>& outputs);

}  // namespace fitcli
