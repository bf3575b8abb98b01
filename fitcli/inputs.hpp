#pragma once
// Input files of the subcommands: "-" means stdin wherever a file is read (docs/cli.md), and the
// --data files of fit and plot: native or pyvisco CSV, EPLEXOR .xls (recognised by its OLE
// signature whatever --format says), pyvisco relaxation tables (t, E_relax).
#include <string>
#include <vector>

#include "fitlib/data/relaxation.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/scene/scene.hpp"

namespace fitcli {

// A path the library's readers can open: `path` itself, or for "-" a temporary copy of stdin
// (read once; a second "-" is a usage error). The copy is named "stdin" in messages.
std::string input_path(const std::string& path);
std::vector<std::string> input_paths(const std::vector<std::string>& paths);

// `text` with the stdin copy's path replaced by "stdin" (error messages, card provenance).
std::string with_stdin_named(std::string text);

// A scene file, or for "-" a scene read from stdin (relative card paths from the current folder).
fitlib::scene::Scene load_scene_input(const std::string& path);

// A fresh path in this process's scratch folder (removed at exit).
std::string scratch_path(const std::string& stem);

// Frequency-domain rows of every file, in order; notes (EPLEXOR shift lists) go to stderr.
fitlib::data::DynamicTestTable read_tables(const std::vector<std::string>& paths, const std::string& format,
                                           const fitlib::data::ReadOptions& read);

// True when --format pyvisco and the first file is a time-domain table.
bool is_relaxation_data(const std::vector<std::string>& paths, const std::string& format);

fitlib::data::RelaxationTable read_relaxation_tables(const std::vector<std::string>& paths);

}  // namespace fitcli
