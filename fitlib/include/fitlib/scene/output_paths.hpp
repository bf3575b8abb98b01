#pragma once
// The files a scene run reads and writes, compared before any work: an output on an input
// replaced it (`life --out-dir cards` over a card named cards/summary.json, `segment_case(s,
// vtk_path=card)` from Python), and a folder's files are outputs as much as --out is
// (docs/cli.md "Conventions", docs/reliability.md §4b).
#include <string>
#include <utility>
#include <vector>

#include "fitlib/scene/scene.hpp"

namespace fitlib::scene {

using NamedPath = std::pair<std::string, std::string>;  // who names it (option, scene key), path

// The names write_outputs gives its files in the output folder (writers.cpp writes under these).
namespace folder_file {
inline constexpr const char* load_history = "load_history.csv";
inline constexpr const char* accumulation = "accumulation.csv";
inline constexpr const char* tension_test = "tension_test.csv";
inline constexpr const char* stress_history = "stress_history.csv";
inline constexpr const char* life = "life.json";
inline constexpr const char* summary = "summary.json";
}  // namespace folder_file

// The files the run reads: the cards the scene names ("belt.materials.<role>", "life.card") and the
// scene file itself ("scene") when it is one (a scene parsed from text has none).
std::vector<NamedPath> scene_inputs(const Scene& scene);

// Every file write_outputs may write into `dir` for this scene, whichever effects the planner then
// runs (load_history.csv, accumulation.csv, tension_test.csv, stress_history.csv, life.json,
// summary.json), and the full-field files of `fitcli life --field-at` (<life_field_prefix>-<k>.vtk).
std::vector<std::string> folder_outputs(const Scene& scene, const std::string& dir);

// UsageError (exit 2) naming the output, the scene key and the file, for an output (option, path;
// empty and "-" skipped) that is one of scene_inputs(scene) by inode or resolved path
// (core::same_file: "./x", symbolic and hard links).
void refuse_outputs_on_inputs(const Scene& scene, const std::vector<NamedPath>& outputs);

}  // namespace fitlib::scene
