#pragma once
// The belt's rubber roles (docs/segment.md "Mesh"): the `bottom` rubber (land and cogs, where the
// radial crack starts) and the `cushion` between it and the cord line (where separation runs). The
// segment's elements, the fatigue module's monitored points and the scene's cards share them, so the
// type lives below all of them (docs/architecture.md). Order: bottom, cushion (arrays by role).
#include <string>

namespace fitlib::core {

enum class MaterialRole { bottom, cushion };

const char* to_string(MaterialRole role);  // "bottom" | "cushion"

// The role named `text`; otherwise an InputError at `key` (and `file`, `line`, `column` when
// given): "unknown <name> '<text>' (expected bottom or cushion)", <name> the key's last part.
MaterialRole material_role_from_string(const std::string& text, const std::string& key, const std::string& file = {},
                                       int line = 0, int column = 0);

}  // namespace fitlib::core
