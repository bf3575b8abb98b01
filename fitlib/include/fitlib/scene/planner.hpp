#pragma once
// The planner: maps the outputs a scene asks for to the effects they need (the registry,
// registry.hpp), adds the refinements listed true in [effects], runs only those and reports per
// effect whether it ran, why, and its cost. An output whose effects this build cannot run is
// listed in Plan::unavailable_outputs with the reason on its effects (docs/belt.md "Planner").
#include <optional>
#include <string>

#include "fitlib/belt/accumulation.hpp"
#include "fitlib/belt/load_cycle.hpp"
#include "fitlib/scene/results.hpp"
#include "fitlib/scene/scene.hpp"
#include "fitlib/scene/writers.hpp"
#include "fitlib/segment/cycle.hpp"

namespace fitlib::scene {

Plan make_plan(const Scene& scene);

// The life's fidelity level: [life] fidelity when given, else the finest level the scene feeds
// and this build has (complete with bottom and cushion cards, elastic with a [segment] table,
// else beam; docs/decisions.md "scene: default fidelity of life").
LifePlan choose_life_plan(const Scene& scene);

// A --field-at word (Scene::life_field_at) checked before anything runs: "entrance" gives NaN, a
// number its path position in mm (>= 0; the cycle length bounds it once the load cycle is known).
// UsageError (exit 2) for anything else, e.g. "banana".
double field_at_mm(const std::string& at);

// The scene's life fields (Scene::life_field_at) before anything runs: each word as field_at_mm
// reads it, and a life at the segment levels (the beam level has no field); UsageError otherwise.
// make_plan calls it; fitcli life calls it before it makes the output folder.
void check_life_fields(const Scene& scene);

// The segment run's equilibrium check as the life reports it (the span increments counted; the
// span cord share's bound the looser one when the run's laws carry history, segment::EquilibriumBounds).
SegmentEquilibrium segment_equilibrium(const segment::CycleResult& run);

SceneResult run_scene(const Scene& scene, const belt::LoadCycleOptions& options = {});

// The scene run with the life asked for (fitcli life, a sweep's life columns, Python's run_life):
// InputError at key life.fidelity, with the planner's reason, when no life comes out.
SceneResult run_life(Scene scene);

// The life on one of several processes that share [life] uncertainty's card draws
// (Scene::draw_executor across processes: fitcli life under mpirun). The process that `writes`
// runs run_life and gets its result; every other one runs only its share of the draws and gets
// nullopt — it needs no deterministic life (docs/sweep.md "The life's card draws under MPI").
// The writer joins the draws' gather also when its life stops before them (its error is then
// rethrown), so no process waits for it. Without a draw executor: run_life.
std::optional<SceneResult> run_life_sharing_draws(const Scene& scene, bool writes);

// The heat sources of a run at the scene's temperature (docs/thermal.md §1): the beam section's
// hysteresis layers and the friction on the run's drive and load cycle, as the heat balance reads
// them at that temperature (without the complete level's segment scaling).
belt::HeatSources heat_sources_of_run(const Scene& scene, const SceneResult& r);

// Belt stiffnesses c, k1, EI at the scene's temperature: [belt.stiffness] overrides first, then
// material cards (cord → c, bottom → E33 for k1 and E22 for EI), then the Fritzson laws of the
// 0.500 in belt with the project's E0/E1 (belt/stiffness.hpp). `source` says which per quantity.
Stiffness resolve_stiffness(const Scene& scene);

// The drive the scene describes (geometry, tensions, belt, friction, speed).
belt::DriveCase make_drive(const Scene& scene, const Stiffness& stiffness);

// The spectrum a scene names: a shape, or the retardation card of a material role.
belt::RetardationSpectrum scene_spectrum(const Scene& scene, const std::string& spec,
                                         std::string* source = nullptr);
// κ = l/R of the scene's drive: centre distance to the next pulley over the driver's radius.
double drive_kappa(const Scene& scene);
AccumulationMap accumulation_map(const belt::RetardationSpectrum& s, const AccumulationSpec& a,
                                 double kappa);

}  // namespace fitlib::scene
