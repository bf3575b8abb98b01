#pragma once
// The scene's effects, one function each, as the registry (registry.cpp) runs them. Internal to
// the scene module.
#include <optional>
#include <string>

#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/segment/point_law.hpp"

namespace fitlib::scene::detail {

// The card of a [belt.materials] role, refused where its temperature law has no material at the
// scene's temperature (card::require_material_at, key conditions.temperature_C) (drive_setup.cpp).
card::Card material_card(const Scene& scene, const std::string& role);
// Adds (once each) a warning per quantity of `at` beyond the role's card's data window, as eval
// would refuse it without --allow-extrapolation (docs/decisions.md "Scenes: a card without a bulk
// modulus converts as eval and export do; a card beyond its data window warns").
void card_window_warnings(const Scene& scene, const std::string& role, const card::Card& card,
                          const model::TestCondition& at, std::vector<std::string>& warnings);

// The segment's material roles by core::MaterialRole, named as core::to_string names them (the
// keys of Scene::materials).
inline constexpr const char* kSegmentRoles[2] = {"bottom", "cushion"};
// The load frequency of a belt element: one load cycle per belt revolution, f = v / L.
inline double load_frequency_Hz(const belt::DriveCase& drive) {
  return drive.belt_speed_mm_s / drive.geometry.belt_length_mm;
}

// The material point of a [belt.materials] role's card at `options` (the segment's fidelity,
// temperature, frequency; the bulk modulus from the card or [belt.materials] poisson_ratio), with
// its data-window warnings; InputError at belt.materials.<role> for what the card cannot give
// (life_effects.cpp; the life's segment levels and `fitcli segment`). At the complete level a damage
// card's damage is held at its tests' drivers (unless [life] beyond_tests = "extrapolate"); `damage_held`
// says whether it was. `amplitude` (elastic fidelity): the strain amplitude the card is read at
// (model::PointOptions::strain_amplitude; a damage card's drivers held as at the complete level).
model::MaterialPointPtr card_point(const Scene& scene, const std::string& role, segment::RoleMaterialOptions options,
                                   std::vector<std::string>& warnings, bool* damage_held = nullptr,
                                   const std::optional<model::Vector6>& amplitude = std::nullopt);

// Belt mechanics (belt_effects.cpp).
ViscoelasticTension viscoelastic_tension(const belt::DriveCase& drive, bool inertia);
CvtThrust cvt_thrust(const belt::DriveCase& drive, const CvtSpec& spec, const belt::LoadCycle* cycle);
TensionTest tension_test(const belt::DriveCase& drive, const TensionTestSpec& spec, double friction);
// The load cycle, timed as the best of three runs (a cycle takes well under a millisecond, so
// single runs would make the refinements' costs, differences of such times, timer noise).
double best_of_three(const belt::DriveCase& drive, const belt::LoadCycleOptions& options,
                     belt::LoadCycle& out);
// Largest relative pointwise change of F, p, γ, K and friction use between two cycles.
EffectChange effect_change(const belt::LoadCycle& with, const belt::LoadCycle& without);

// Heat build-up (heat_effects.cpp; docs/thermal.md): the heat sources of a load cycle at the scene's
// temperature, and the effect: the belt temperature's fixed point, the stiffness, drive and load
// cycle re-made at it.
// `warnings`: the cards' data-window warnings at the layers' amplitudes (nullptr: none).
belt::HeatSources heat_sources(const Scene& scene, const belt::DriveCase& drive, const belt::LoadCycle& cycle,
                               std::vector<std::string>* warnings = nullptr);
void heat_buildup(const Scene& scene, SceneResult& r);
// √2 × the rms of σ12 about its mean over one period of a periodic history (trapezoidal in time,
// closed back to the first sample): the cushion's shear amplitude the heat source reads, the
// sinusoid's that dissipates as much in a linear viscoelastic solid of frequency-flat G″.
double equivalent_amplitude(const std::vector<fatigue::StressSample>& history, double period_s);
// The same of any periodic history x(t_s) (the stretch layers' ε22(d, t)).
double periodic_amplitude(const std::vector<double>& t_s, const std::vector<double>& x, double period_s);

// Life (life_effects.cpp).
// Why this build cannot run the segment levels (elastic, complete); nullopt once it can.
void segment_stresses(const Scene& scene, SceneResult& r);
void beam_stresses(const Scene& scene, SceneResult& r);
void fatigue_life(const Scene& scene, SceneResult& r);
// [life] uncertainty = "cards": B10/B50's interval over lives on draws of the cards (card_uncertainty.cpp).
void card_uncertainty(const Scene& scene, SceneResult& r, LifeResult& life);

// Runs f, adding the scene file to an InputError a library call raised without one.
template <typename F>
auto in_scene(const Scene& scene, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const core::InputError& e) {
    if (!e.file().empty()) throw;
    throw core::InputError(e.detail().empty() ? e.what() : e.detail(), scene.path, 0, 0, e.key());
  }
}
}  // namespace fitlib::scene::detail
