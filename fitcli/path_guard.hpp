#pragma once
// Outputs that would replace an input, or one another, are refused before any work: `fit --data
// d.csv --out d.csv` replaced the table it read, `life-fit --out X --peaks-out X` lost one of its
// two files (docs/cli.md "Conventions", docs/reliability.md).
#include <CLI/CLI.hpp>

namespace fitcli {

// Checks the file options of the subcommand(s) `app` parsed: every output file (--out, --plot,
// --vtk, --surface-out, --shifts-out, --peaks-out) against every input file (--data, --card,
// --scene, --sweep, --shifts, ...) and against the other outputs, by inode and resolved path
// (core::same_file). UsageError naming both options and the file; also for one input file given
// twice to one option (its rows would count twice).
void refuse_colliding_paths(const CLI::App& app);

}  // namespace fitcli
