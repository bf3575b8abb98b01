#pragma once
// A scene from an already parsed TOML table: sweeps (sweep.hpp) parse a base scene once and set
// dotted keys in copies of it, one per case, without printing and re-reading TOML text.
#include <string>

#include <toml++/toml.h>

#include "fitlib/scene/scene.hpp"

namespace fitlib::scene {

// TOML text checked against core::toml_limits and parsed; InputError naming source:line:column.
toml::table parse_scene_toml(const std::string& text, const std::string& source);

// The scene of `root` with full validation (as parse_scene); relative paths resolve against the
// folder of `source`.
Scene parse_scene_table(const toml::table& root, const std::string& source);

}  // namespace fitlib::scene
