#pragma once
// The planner's effect registry (ARCHITECTURE.md: "each effect declared once (name, needs,
// produces, cost), its result typed"). The planner reads only this table to decide what runs;
// how to add an effect: docs/belt.md "Planner".
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fitlib/scene/results.hpp"
#include "fitlib/scene/scene.hpp"

namespace fitlib::scene {

struct Effect {
  std::string name;
  std::string produces;  // the SceneResult slot it fills
  std::string cost;      // how its wall time is measured
  // What asks for it: requested [outputs] keys that need it, and its own [effects] key.
  std::vector<std::string> outputs;
  std::string effects_key;
  // Effects whose results it reads (earlier in the registry). A function of the scene because
  // life's stress source follows the fidelity level.
  std::function<std::vector<std::string>(const Scene&)> needs;
  // For a load-cycle refinement: the switch it turns on in the load cycle it refines
  // (`refines`); it runs only when that effect runs.
  std::string refines;
  bool belt::LoadCycleEffects::*load_cycle_switch = nullptr;
  // Why this build cannot run it; nullopt (or empty function): it can.
  std::function<std::optional<std::string>()> unavailable;
  // Runs it on the results of its needs and returns its cost in seconds, measured as `cost` says.
  std::function<double(const Scene&, SceneResult&)> run;
};

// All effects in run order (each after the effects it needs).
const std::vector<Effect>& effect_registry();

}  // namespace fitlib::scene
