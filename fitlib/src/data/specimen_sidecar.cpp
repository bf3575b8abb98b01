// The JSON specimen sidecar of a waveform record (formats.md §2): an object of specimen keys
// that must agree with the `# key = value` lines of the signals file.
#include "fitlib/core/json.hpp"
#include "specimen_keys.hpp"

namespace fitlib::data::specimen_keys {

void apply_sidecar(SpecimenInfo& info, const nlohmann::json& from_lines,
                   const std::string& sidecar_path, const std::string& signals_path) {
  const nlohmann::json sidecar = core::load_json(sidecar_path);
  if (!sidecar.is_object())
    throw core::InputError("specimen sidecar must be a JSON object", sidecar_path);
  for (const auto& [key, value] : sidecar.items()) {
    const auto error = [&, key = key](const std::string& message) {
      return core::InputError(message, sidecar_path, 0, 0, key);
    };
    if (from_lines.contains(key) &&
        !(from_lines[key] == value ||
          (value.is_number() && from_lines[key].is_number() &&
           from_lines[key].get<double>() == value.get<double>())))
      throw error("differs from the '# " + key + " = ...' line of " + signals_path);
    apply(info, key, value, error);
  }
}

}  // namespace fitlib::data::specimen_keys
