#pragma once
// The stress level of a belt life (docs/fatigue.md §"Life of a scene", docs/segment.md "Levels"):
// `beam` the layered section's closed forms, `elastic` the segment FE with each card's elastic
// equivalent (its storage stiffness at the run's temperature and load frequency), `complete` the
// segment FE with each card's full model. The vocabulary the material point (model: complete =
// the full law, elastic = its equivalent), the segment, fatigue (the level a law's constants were
// fitted at) and the scene share, so it lives below all of them (docs/architecture.md).
#include <string>

namespace fitlib::core {

enum class Fidelity { beam, elastic, complete };

const char* to_string(Fidelity fidelity);  // "beam" | "elastic" | "complete"

// The level named `text`; otherwise an InputError at `key` (and `file`, `line`, `column` when
// given): "unknown <name> '<text>' (expected beam, elastic or complete)", <name> the key's last part.
Fidelity fidelity_from_string(const std::string& text, const std::string& key, const std::string& file = {},
                              int line = 0, int column = 0);

}  // namespace fitlib::core
