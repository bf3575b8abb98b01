// The heat build-up effect (docs/thermal.md): the belt's temperature as the fixed point of its
// heat balance, with the stiffness, drive and load cycle re-made at every iterate's temperature.
#include <algorithm>
#include <array>
#include <cmath>

#include "effects.hpp"
#include "fitlib/belt/heat.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/fatigue/beam_section.hpp"

namespace fitlib::scene::detail {
namespace {

// Storage and loss modulus of a [belt.materials] role at `at` (uniaxial 22 for the bottom rubber,
// shear for the cushion); without a card E′ = `fallback_MPa` and E″ = E′ tan δ ([thermal] loss_angle_deg).
// `warnings` (the fixed point's run only) gets the card's data-window warnings at the layer's amplitude.
std::array<double, 2> layer_moduli(const Scene& s, const std::string& role, model::TestCondition at,
                                   double fallback_MPa, std::vector<std::string>* warnings) {
  if (!s.materials.count(role))
    return {fallback_MPa, belt::loss_modulus_of_storage_MPa(fallback_MPa, s.thermal.loss_angle_deg)};
  const card::Card c = material_card(s, role);
  if (warnings) card_window_warnings(s, role, c, at, *warnings);
  try {
    const auto m = card::moduli_in_mode(*c.model(), c.values(), at, s.material_poisson_ratio);
    return {m.storage, m.loss};
  } catch (const std::exception& e) {
    throw core::InputError(std::string("card cannot give the loss modulus the heat build-up needs: ") + e.what(), {},
                           0, 0, "belt.materials." + role);
  }
}

// ε22(d) of the beam level, (1 + F/c)(1 − K d)/(1 − K_m d) − 1, and its amplitude over the cycle.
double stretch_amplitude(const belt::LoadCycle& cycle, const belt::DriveCase& drive, double K_m, double d_mm) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const belt::LoadSample& q : cycle.samples) {
    const double e = (1.0 + q.F_N / drive.belt.c_N) * (1.0 - q.K_1_mm * d_mm) / (1.0 - K_m * d_mm) - 1.0;
    lo = std::min(lo, e), hi = std::max(hi, e);
  }
  return 0.5 * (hi - lo);
}

// ∫ ε_a(d)² over [d0, d1] by 3-point Gauss–Legendre (ε_a is nearly linear in d: exact to O(h⁶)).
double mean_square_amplitude(const belt::LoadCycle& cycle, const belt::DriveCase& drive, double K_m, double d0,
                             double d1) {
  static const double x[3] = {-0.7745966692414834, 0.0, 0.7745966692414834}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double a = stretch_amplitude(cycle, drive, K_m, 0.5 * (d0 + d1) + 0.5 * (d1 - d0) * x[k]);
    sum += 0.5 * w[k] * a * a;
  }
  return sum;  // the mean over the interval
}

// The layers of the beam section at `s`'s temperature: the bottom rubber stretched and bent (land
// and cogs), the cushion bent and sheared by the friction (σ12 of the mid-cushion point).
std::vector<belt::HysteresisLayer> beam_layers(const Scene& s, const belt::DriveCase& drive,
                                               const belt::LoadCycle& cycle, std::vector<std::string>* warnings) {
  const fatigue::BeamSection sec = fatigue::default_beam_section(drive, s.temperature_C);
  const double L = drive.geometry.belt_length_mm, B = drive.belt.width_mm, K_m = sec.manufactured_curvature_1_mm;
  model::TestCondition at;
  at.temperature_C = s.temperature_C, at.frequency_Hz = load_frequency_Hz(drive);
  std::vector<belt::HysteresisLayer> layers;
  auto add = [&](const char* name, const std::string& role, model::TestMode mode, const char* orientation,
                 double volume_mm3, double amplitude, double fallback_MPa) {
    at.mode = mode, at.orientation = orientation, at.strain_amplitude = amplitude;
    layers.push_back({name, volume_mm3, layer_moduli(s, role, at, fallback_MPa, warnings)[1], amplitude});
  };
  const double land = sec.land_depth_mm - sec.cushion_mm, cogs = sec.cog_depth_mm;
  const double ms_land = mean_square_amplitude(cycle, drive, K_m, sec.cushion_mm, sec.land_depth_mm);
  const double ms_cogs = mean_square_amplitude(cycle, drive, K_m, sec.land_depth_mm, sec.land_depth_mm + cogs);
  add("bottom rubber, land", "bottom", model::TestMode::uniaxial, "22", B * land * L, std::sqrt(ms_land),
      sec.bottom_modulus_MPa);
  add("bottom rubber, cogs", "bottom", model::TestMode::uniaxial, "22", B * sec.cog_fill * cogs * L,
      std::sqrt(ms_cogs), sec.bottom_modulus_MPa);
  add("cushion, stretch", "cushion", model::TestMode::uniaxial, "22", B * sec.cushion_mm * L,
      std::sqrt(mean_square_amplitude(cycle, drive, K_m, 0.0, sec.cushion_mm)), sec.cushion_modulus_MPa);
  // The cushion's shear: γ_a = τ_a/|G*| from the friction shear of the beam level's mid-cushion point.
  double tau_lo = HUGE_VAL, tau_hi = -HUGE_VAL;
  for (const fatigue::PointHistory& p : fatigue::beam_stress_histories(cycle, drive, sec))
    if (p.role == fatigue::Role::cushion)
      for (const fatigue::StressSample& q : p.samples) tau_lo = std::min(tau_lo, q.s12_MPa), tau_hi = std::max(tau_hi, q.s12_MPa);
  const double tau_a = tau_hi > tau_lo ? 0.5 * (tau_hi - tau_lo) : 0.0;
  at.mode = model::TestMode::shear, at.orientation = "", at.strain_amplitude = tau_a / (sec.cushion_modulus_MPa / 3.0);
  const auto G = layer_moduli(s, "cushion", at, sec.cushion_modulus_MPa / 3.0, nullptr);
  add("cushion, shear", "cushion", model::TestMode::shear, "", B * sec.cushion_mm * L, tau_a / std::hypot(G[0], G[1]),
      sec.cushion_modulus_MPa / 3.0);
  return layers;
}

}  // namespace

belt::HeatSources heat_sources(const Scene& s, const belt::DriveCase& drive, const belt::LoadCycle& cycle,
                               std::vector<std::string>* warnings) {
  belt::HeatSources h;
  h.layers = beam_layers(s, drive, cycle, warnings);
  h.hysteresis_W = belt::hysteresis_power_W(h.layers, load_frequency_Hz(drive));
  h.friction_W = belt::friction_power_W(cycle, drive.belt);
  return h;
}

namespace {

// Segment runs of the complete level's heat balance at most, and when their ratio has settled.
constexpr int kMaxSegmentRuns = 4;
constexpr double kSegmentRatioTolerance = 1e-3;

// The segment's own hysteresis (W per belt) at `at`'s temperature on that temperature's drive and
// load cycle: the complete level's run, without field output.
double segment_hysteresis_W(const Scene& at, const SceneResult& r, const belt::DriveCase& drive,
                            const belt::LoadCycle& cycle) {
  Scene quiet = at;
  quiet.life_field_at.clear();
  SceneResult run;
  run.plan = r.plan, run.drive = drive, run.cycle = cycle;
  segment_stresses(quiet, run);
  return *run.segment_hysteresis_W;
}

}  // namespace

void heat_buildup(const Scene& s, SceneResult& r) {
  Scene at = s;
  std::optional<Stiffness> stiffness;
  std::optional<belt::DriveCase> drive;
  std::optional<belt::LoadCycle> cycle;
  std::vector<std::string> warnings;
  std::vector<std::string>* collect = nullptr;  // the fixed point's run only
  double segment_over_layers = 1.0;             // the complete level's segment runs set it
  auto remake = [&](double T) {  // the cards' moduli at T in every stiffness, the load cycle on them
    at.temperature_C = T;
    try {
      stiffness = resolve_stiffness(at);
      drive = make_drive(at, *stiffness);
      cycle = belt::compute_load_cycle(*drive, r.load_cycle_options);
      belt::HeatSources h = heat_sources(at, *drive, *cycle, collect);
      h.hysteresis_W *= segment_over_layers;
      return h;
    } catch (const core::InputError& e) {  // the heat, not the scene, took the belt where its inputs end
      if (T == s.thermal.ambient_C) throw;  // the first iterate: the scene's own inputs at the ambient
      throw core::NumericalError("thermal runaway: the heat balance takes the belt to " + core::short_number(T) +
                                 " degC, where " + (e.detail().empty() ? std::string(e.what()) : e.detail()) +
                                 " (docs/thermal.md §4)");
    }
  };
  r.heat = belt::solve_belt_temperature(*r.drive, s.thermal, remake);
  // The complete level: the segment's dissipation at each fixed point's temperature replaces the
  // layers' estimate, their ratio carried to the next fixed point (docs/thermal.md §1).
  const bool complete = r.plan.life && r.plan.life->fidelity == core::Fidelity::complete;
  for (int run = 1; complete && run <= kMaxSegmentRuns; ++run) {
    const double layers_W = remake(r.heat->temperature_C).hysteresis_W / segment_over_layers;
    const double ratio = segment_hysteresis_W(at, r, *drive, *cycle) / layers_W;
    const bool settled = std::abs(ratio - segment_over_layers) <= kSegmentRatioTolerance * ratio;
    segment_over_layers = ratio;
    r.heat = belt::solve_belt_temperature(*r.drive, s.thermal, remake);
    r.heat->segment_over_layers = ratio, r.heat->segment_runs = run;
    if (settled) break;
  }
  collect = &warnings;
  remake(r.heat->temperature_C);  // what the stresses and the life see
  r.stiffness = std::move(stiffness), r.drive = std::move(drive), r.cycle = std::move(cycle);
  r.warnings = r.stiffness->warnings;
  for (std::string& w : warnings)
    if (std::find(r.warnings.begin(), r.warnings.end(), w) == r.warnings.end()) r.warnings.push_back(std::move(w));
}

}  // namespace fitlib::scene::detail
