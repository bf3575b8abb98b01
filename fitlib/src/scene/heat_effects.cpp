// The heat build-up effect (docs/thermal.md): the belt's temperature as the fixed point of its
// heat balance, with the stiffness, drive and load cycle re-made at every iterate's temperature.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "effects.hpp"
#include "fitlib/belt/heat.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/core/quadrature.hpp"
#include "fitlib/fatigue/beam_section.hpp"

namespace fitlib::scene::detail {
namespace {

// The scene's cards of the heat layers' roles, each read from its file once per set of layers.
struct LayerCard {
  card::Card card;
  model::ModelPtr model;
};
using LayerCards = std::map<std::string, LayerCard>;

LayerCards layer_cards(const Scene& s) {
  LayerCards out;
  for (const char* role : {"bottom", "cushion"})
    if (s.materials.count(role)) {
      card::Card c = material_card(s, role);
      model::ModelPtr m = c.model();
      out.emplace(role, LayerCard{std::move(c), std::move(m)});
    }
  return out;
}

// Storage and loss modulus of a role's card at `at`.
model::Moduli<double> card_moduli(const Scene& s, const std::string& role, const LayerCard& c,
                                  const model::TestCondition& at) {
  try {
    return card::moduli_in_mode(*c.model, c.card.values(), at, s.material_poisson_ratio);
  } catch (const std::exception& e) {
    throw core::InputError(std::string("card cannot give the loss modulus the heat build-up needs: ") + e.what(), {},
                           0, 0, "belt.materials." + role);
  }
}

// Storage and loss modulus of a [belt.materials] role at `at` (uniaxial 22 for the bottom rubber,
// shear for the cushion); without a card E′ = `fallback_MPa` and E″ = E′ tan δ ([thermal] loss_angle_deg).
// `warnings` (the fixed point's run only) gets the card's data-window warnings at the layer's amplitude.
std::array<double, 2> layer_moduli(const Scene& s, const LayerCards& cards, const std::string& role,
                                   model::TestCondition at, double fallback_MPa, std::vector<std::string>* warnings) {
  const auto c = cards.find(role);
  if (c == cards.end()) return {fallback_MPa, belt::loss_modulus_of_storage_MPa(fallback_MPa, s.thermal.loss_angle_deg)};
  if (warnings) card_window_warnings(s, role, c->second.card, at, *warnings);
  const auto m = card_moduli(s, role, c->second, at);
  return {m.storage, m.loss};
}

// The shear strain amplitude of a stress amplitude τ_a read stress-controlled on a role's card:
// the fixed point γ = τ_a/|G*(γ)|, iterated from γ = τ_a/G_section. A filled rubber's |G*| falls
// with the amplitude, so τ_a/|G*(γ)| rises with γ and the iterates move monotonically to the fixed
// point next to the start (the amplitude reached loading from small ones); without a card |G*| is
// the section's G with G″ = G tan δ, one step. A few card evaluations; at most 100.
double stress_controlled_shear(const Scene& s, const LayerCards& cards, const std::string& role,
                               model::TestCondition at, double tau_a, double G_section_MPa) {
  if (!(tau_a > 0.0)) return 0.0;
  const auto c = cards.find(role);
  if (c == cards.end())
    return tau_a / std::hypot(G_section_MPa, belt::loss_modulus_of_storage_MPa(G_section_MPa, s.thermal.loss_angle_deg));
  double gamma = tau_a / G_section_MPa;
  for (int k = 0; k < 100; ++k) {
    at.strain_amplitude = gamma;
    const auto m = card_moduli(s, role, c->second, at);
    const double next = tau_a / std::hypot(m.storage, m.loss);
    const bool settled = std::abs(next - gamma) <= 1e-9 * next;
    gamma = next;
    if (settled) break;
  }
  return gamma;
}

// ε22(d) of the beam level, (1 + F/c)(1 − K d)/(1 − K_m d) − 1, and its equivalent amplitude over
// the cycle: √2 × its rms about the mean (periodic_amplitude), as the friction shear's. The bending
// strain is a pulse too (compressed over each wrap arc, near the mould's over the spans), and the
// sinusoid of half its range dissipates 0.60–0.74× what it does at 1–6 mm on the medium drive
// (docs/decisions.md "Heat: the bottom rubber's stretch by its rms amplitude, at the plane-strain
// modulus").
double stretch_amplitude(const belt::LoadCycle& cycle, const belt::DriveCase& drive, double K_m, double d_mm) {
  std::vector<double> t, e;
  t.reserve(cycle.samples.size()), e.reserve(cycle.samples.size());
  for (const belt::LoadSample& q : cycle.samples) {
    t.push_back(q.t_s);
    e.push_back(fatigue::layer_stretch(q.F_N / drive.belt.c_N, q.K_1_mm, K_m, d_mm));
  }
  return periodic_amplitude(t, e, cycle.cycle_time_s);
}

// ∫ ε_a(d)² over [d0, d1] by 3-point Gauss–Legendre (ε_a is nearly linear in d: exact to O(h⁶)).
double mean_square_amplitude(const belt::LoadCycle& cycle, const belt::DriveCase& drive, double K_m, double d0,
                             double d1) {
  double sum = 0.0;
  for (const core::QuadraturePoint& q : core::gauss_legendre_3(d0, d1)) {
    const double a = stretch_amplitude(cycle, drive, K_m, q.x);
    sum += q.mean_weight * a * a;
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
  const LayerCards cards = layer_cards(s);
  // `plane`: the along-belt stretch of the wide section (ε33 = 0), whose stress per strain is the
  // plane-strain modulus E/(1 − ν²), as the beam level's σ22 (docs/fatigue.md §5) and the segment's
  // plane-strain points: its loss modulus E″/(1 − ν²) (4/3 E″ for a nearly incompressible rubber).
  const double plane = 1.0 / (1.0 - sec.poisson * sec.poisson);
  auto add = [&](const char* name, const std::string& role, model::TestMode mode, const char* orientation,
                 double volume_mm3, double amplitude, double fallback_MPa, double factor) {
    at.mode = mode, at.orientation = orientation, at.strain_amplitude = amplitude;
    layers.push_back({name, volume_mm3, factor * layer_moduli(s, cards, role, at, fallback_MPa, warnings)[1], amplitude});
  };
  const double land = sec.land_depth_mm - sec.cushion_mm, cogs = sec.cog_depth_mm;
  const double ms_land = mean_square_amplitude(cycle, drive, K_m, sec.cushion_mm, sec.land_depth_mm);
  const double ms_cogs = mean_square_amplitude(cycle, drive, K_m, sec.land_depth_mm, sec.land_depth_mm + cogs);
  add("bottom rubber, land", "bottom", model::TestMode::uniaxial, "22", B * land * L, std::sqrt(ms_land),
      sec.bottom_modulus_MPa, plane);
  add("bottom rubber, cogs", "bottom", model::TestMode::uniaxial, "22", B * sec.cog_fill * cogs * L,
      std::sqrt(ms_cogs), sec.bottom_modulus_MPa, plane);
  // The friction shear: γ_a = τ_a/|G*| read stress-controlled, τ_a the equivalent amplitude of the beam
  // level's mid-cushion history (√2 rms about the mean: the friction shear is a pulse over the sliding
  // arcs, not a sinusoid of half its range; docs/decisions.md "Heat: the beam and elastic levels'
  // friction shear by its rms amplitude").
  double tau_a = 0.0, h_mid = 0.0;
  const double period_s = cycle.cycle_time_s;  // one load cycle: the belt length at its speed
  for (const fatigue::PointHistory& p : fatigue::beam_stress_histories(cycle, drive, sec))
    if (p.role == fatigue::Role::cushion) tau_a = std::max(tau_a, equivalent_amplitude(p.samples, period_s));
  h_mid = sec.land_depth_mm - 0.5 * sec.cushion_mm + sec.cog_fill * sec.cog_depth_mm;
  // The bottom rubber below the cushion is sheared by the same body force: σ12(d) = B_l h(d), h the
  // rubber below depth d (land: land − d + fill · cogs; in a cog: land + cogs − d), so τ_a(d) =
  // τ_a h(d)/h_mid. Per region one layer whose E″ ε_a² is the 3-point Gauss–Legendre mean over depth
  // of G″(γ(d)) γ(d)², each γ(d) read stress-controlled on the bottom card (shear 12).
  auto bottom_shear = [&](const char* name, double volume_mm3, double d0, double d1, auto below_mm) {
    model::TestCondition q = at;
    q.mode = model::TestMode::shear, q.orientation = "12";
    const double G = sec.bottom_modulus_MPa / 3.0;
    double work = 0.0, square = 0.0;  // means of G″ γ² and γ²
    for (const core::QuadraturePoint& p : core::gauss_legendre_3(d0, d1)) {
      const double gamma = stress_controlled_shear(s, cards, "bottom", q, tau_a * below_mm(p.x) / h_mid, G);
      q.strain_amplitude = gamma;
      work += p.mean_weight * layer_moduli(s, cards, "bottom", q, G, warnings)[1] * gamma * gamma;
      square += p.mean_weight * gamma * gamma;
    }
    layers.push_back({name, volume_mm3, square > 0.0 ? work / square : 0.0, std::sqrt(square)});
  };
  bottom_shear("bottom rubber, land shear", B * land * L, sec.cushion_mm, sec.land_depth_mm,
               [&](double d) { return sec.land_depth_mm - d + sec.cog_fill * cogs; });
  bottom_shear("bottom rubber, cogs shear", B * sec.cog_fill * cogs * L, sec.land_depth_mm, sec.land_depth_mm + cogs,
               [&](double d) { return sec.land_depth_mm + cogs - d; });
  add("cushion, stretch", "cushion", model::TestMode::uniaxial, "22", B * sec.cushion_mm * L,
      std::sqrt(mean_square_amplitude(cycle, drive, K_m, 0.0, sec.cushion_mm)), sec.cushion_modulus_MPa, plane);
  at.mode = model::TestMode::shear, at.orientation = "";
  add("cushion, shear", "cushion", model::TestMode::shear, "", B * sec.cushion_mm * L,
      stress_controlled_shear(s, cards, "cushion", at, tau_a, sec.cushion_modulus_MPa / 3.0), sec.cushion_modulus_MPa / 3.0,
      1.0);
  return layers;
}

}  // namespace

// √2 × the rms about its mean of a periodic history x(t) over one period (trapezoidal in t, closed
// from the last sample back to the first one period on): the amplitude of the sinusoid that
// dissipates as much per cycle as the history in a linear viscoelastic solid whose loss modulus does
// not change with frequency (Parseval: W = π Σ_n G″(n f) x_n², Σ_n x_n² = 2 var x). A sinusoid gives
// its amplitude; a pulse of height h over a share φ of the cycle h √(2 φ (1 − φ)), not h/2.
double periodic_amplitude(const std::vector<double>& t_s, const std::vector<double>& x, double period_s) {
  if (t_s.size() < 2 || !(period_s > 0.0)) return 0.0;
  double sum = 0.0, sum2 = 0.0;
  auto add = [&](double a, double b, double dt) {
    sum += 0.5 * dt * (a + b), sum2 += 0.5 * dt * (a * a + b * b);
  };
  for (std::size_t k = 1; k < t_s.size(); ++k) add(x[k - 1], x[k], t_s[k] - t_s[k - 1]);
  const double closing = period_s - (t_s.back() - t_s.front());
  if (closing > 0.0) add(x.back(), x.front(), closing);
  const double mean = sum / period_s;
  return std::sqrt(2.0 * std::max(0.0, sum2 / period_s - mean * mean));
}

double equivalent_amplitude(const std::vector<fatigue::StressSample>& q, double period_s) {
  std::vector<double> t, x;
  for (const fatigue::StressSample& p : q) t.push_back(p.t_s), x.push_back(p.s12_MPa);
  return periodic_amplitude(t, x, period_s);
}

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
