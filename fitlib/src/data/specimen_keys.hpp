#pragma once
// The specimen keys of a waveform record (formats.md §2), shared by the `# key = value` lines of
// the signals file (waveform_file.cpp) and the JSON sidecar (specimen_sidecar.cpp).
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "fitlib/core/error.hpp"
#include "fitlib/data/specimen.hpp"

namespace fitlib::data::specimen_keys {

// Builds the error for a key at its place (file and line, or file and key).
using ErrorAt = std::function<core::InputError(const std::string& message)>;

// True for keys whose value is a number (a `# key = value` text is parsed as one).
bool is_numeric(const std::string& key);

// Checks `value` for `key` and stores it in `info`; unknown keys and bad values throw error(...).
void apply(SpecimenInfo& info, const std::string& key, const nlohmann::json& value,
           const ErrorAt& error);

// The sidecar's keys onto `info`; a key also given by a `# key = value` line (`from_lines`, key →
// value) must agree with it. Errors name the sidecar and the key.
void apply_sidecar(SpecimenInfo& info, const nlohmann::json& from_lines,
                   const std::string& sidecar_path, const std::string& signals_path);

}  // namespace fitlib::data::specimen_keys
