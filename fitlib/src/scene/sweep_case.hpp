#pragma once
// The scene of one sweep case: the base scene's TOML with the [set] keys and the case's axis
// values set at their dotted key paths, then validated as any scene (scene_toml.hpp).
#include <toml++/toml.h>

#include "fitlib/scene/scene.hpp"
#include "fitlib/scene/sweep.hpp"

namespace fitlib::scene {

// Sets `value` at `key_path` ("a.b[2].c"): missing tables on the way are created, array elements
// must exist. std::invalid_argument with the reason when the path does not fit the table.
void set_key_path(toml::table& root, const std::string& key_path, const SweepValue& value);

Scene case_scene(const Sweep& sweep, const SweepCase& c);

// Each [set] value and axis value tried alone on the first scene (each scene with the first
// values), so a key the scene format rejects is a sweep-file error naming the value's line.
void validate_sweep_values(const Sweep& sweep, const toml::table& sweep_root);

// The work cap in core-hours (sweep_cost_core_hours above kMaxSweepCoreHours): InputError naming
// the sweep file, key life.fidelity and the estimate, before the first case runs.
void check_sweep_cost(const Sweep& sweep);

}  // namespace fitlib::scene
