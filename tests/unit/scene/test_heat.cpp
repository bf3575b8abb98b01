// The heat build-up of a scene (docs/thermal.md): off changes nothing, the balance closes at the
// fixed point, the temperature rises with torque and speed on the bundled drives, and the life runs
// at the belt's temperature.
#include <gtest/gtest.h>

#include <cmath>

#include "../../../fitlib/src/scene/effects.hpp"
#include "common/temp_path.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/fatigue/beam_section.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"
#include "fitlib/scene/writers.hpp"

using namespace fitlib;

namespace {

const std::string kDrives = FITLIB_SOURCE_DIR "/datasets/drives/";

scene::Scene drive(const std::string& load, bool heat, double ambient_C = 25.0) {
  auto s = scene::load_scene(kDrives + "ref-0500-" + load + ".toml");
  s.outputs["life"] = true;
  if (heat) s.effects["heat_buildup"] = true, s.ambient_C = ambient_C, s.thermal.ambient_C = ambient_C;
  return s;
}

// [effects] heat_buildup = false (or absent) leaves the life at [conditions] temperature_C, bit for bit.
TEST(SceneHeat, OffGivesTodaysLivesBitForBit) {
  for (const char* load : {"light", "medium", "heavy"}) {
    auto absent = drive(load, false), off = drive(load, false);
    off.effects["heat_buildup"] = false;
    const auto a = scene::run_life(absent), b = scene::run_life(off);
    EXPECT_FALSE(a.heat || b.heat);
    ASSERT_EQ(a.life->report.modes.size(), b.life->report.modes.size());
    for (std::size_t k = 0; k < a.life->report.modes.size(); ++k)
      EXPECT_EQ(a.life->report.modes[k].life_cycles, b.life->report.modes[k].life_cycles);
    EXPECT_EQ(scene::life_json(absent, a, false).dump(), scene::life_json(off, b, false).dump());
    EXPECT_EQ(scene::life_json(absent, a, false)["temperature_C"], 80.0);  // the scene's, as before
    // Today's route: the fatigue module's own beam level at the scene's temperature (as SceneLife tests it).
    const auto d = scene::make_drive(absent, scene::resolve_stiffness(absent));
    belt::LoadCycleOptions o;
    o.effects = scene::make_plan(absent).load_cycle;
    const auto cycle = belt::compute_load_cycle(d, o);
    const auto direct = fatigue::beam_life(cycle, d, fatigue::default_beam_section(d, 80.0),
                                           fatigue::card_at_level(fatigue::default_card(), core::Fidelity::beam), 80.0);
    for (std::size_t k = 0; k < direct.modes.size(); ++k)
      EXPECT_EQ(a.life->report.modes[k].life_cycles, direct.modes[k].life_cycles) << load;
  }
}

// Sources (re-made independently at the fixed point's temperature) equal the losses to 1e-6.
TEST(SceneHeat, EnergyBalanceClosesAtTheFixedPoint) {
  for (const char* load : {"light", "heavy"}) {
    const auto s = drive(load, true);
    const auto r = scene::run_life(s);
    ASSERT_TRUE(r.heat);
    const double T = r.heat->temperature_C;
    scene::Scene at = s;
    at.temperature_C = T;
    const auto d = scene::make_drive(at, scene::resolve_stiffness(at));
    belt::LoadCycleOptions o;
    o.effects = scene::make_plan(s).load_cycle;
    const auto cycle = belt::compute_load_cycle(d, o);
    const belt::HeatSources q = scene::detail::heat_sources(at, d, cycle);
    const belt::HeatPaths p = belt::heat_paths(d, s.thermal, T);
    const double in = q.hysteresis_W + p.friction_to_belt * q.friction_W;
    double out = p.convection_W_K * (T - s.thermal.ambient_C);
    for (double g : p.contact_W_K) out += g * (T - p.pulley_C);
    EXPECT_NEAR(out / in, 1.0, 1e-6) << load;
    EXPECT_GT(T, 25.0);
    EXPECT_GT(r.heat->iterations, 1);
    // The life ran at the belt's temperature.
    EXPECT_EQ(r.life_conditions->temperature_C, T);
  }
}

TEST(SceneHeat, TemperatureRisesWithTorqueAndSpeedOnTheBundledDrives) {
  double last = -HUGE_VAL;
  for (const char* load : {"light", "medium", "heavy", "severe"}) {
    auto s = drive(load, true);
    s.outputs["life"] = false;
    const auto r = scene::run_scene(s);
    ASSERT_TRUE(r.heat) << load;
    EXPECT_GT(r.heat->temperature_C, last) << load;
    last = r.heat->temperature_C;
  }
  last = -HUGE_VAL;
  for (double rpm : {1000.0, 2000.0, 3000.0, 4500.0}) {
    auto s = drive("medium", true);
    s.outputs["life"] = false;
    s.pulleys[0].speed_rpm = rpm;
    const auto r = scene::run_scene(s);
    EXPECT_GT(r.heat->temperature_C, last) << rpm;
    last = r.heat->temperature_C;
  }
}

TEST(SceneHeat, SceneKeysAndErrors) {
  const std::string base = "[drive]\ncenter_distance_mm = 300\npulleys = [ {name = \"a\", pitch_diameter_mm = 100, "
                           "role = \"driver\", speed_rpm = 3000}, {name = \"b\", pitch_diameter_mm = 100, role = "
                           "\"driven\"} ]\ntorque_Nm = 15\ninitial_tension_N = 600\n";
  EXPECT_THROW(scene::parse_scene(base + "[effects]\nheat_buildup = true\n", "h.toml"), core::InputError);
  const auto s = scene::parse_scene(base + "[effects]\nheat_buildup = true\n[conditions]\nambient_C = 30\n"
                                           "[thermal]\nconvection_W_m2K = 50\npulley_C = 45\n", "h.toml");
  EXPECT_EQ(s.thermal.ambient_C, 30.0);
  EXPECT_EQ(s.thermal.convection_W_m2K, 50.0);
  const auto r = scene::run_scene(s);
  ASSERT_TRUE(r.heat);
  EXPECT_EQ(r.heat->paths.convection_W_m2K, 50.0);
  EXPECT_EQ(r.heat->paths.pulley_C, 45.0);
  EXPECT_THROW(scene::parse_scene(base + "[thermal]\nconvection = 50\n", "h.toml"), core::InputError);
  // A belt that makes its heat faster than it loses it: exit 4, "thermal runaway".
  auto hot = s;
  hot.thermal.convection_W_m2K = 1e-3, hot.thermal.contact_W_m2K = 0.0, hot.thermal.max_temperature_C = 120.0;
  try {
    scene::run_scene(hot);
    FAIL() << "no runaway";
  } catch (const core::NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("thermal runaway"), std::string::npos) << e.what();
  }
}

// The medium drive without cards at its temperature: its drive, load cycle and beam section.
struct MediumBeam {
  scene::Scene scene = ::drive("medium", false);
  belt::DriveCase drive_case = scene::make_drive(scene, scene::resolve_stiffness(scene));
  belt::LoadCycle cycle = belt::compute_load_cycle(drive_case, options());
  fatigue::BeamSection section = fatigue::default_beam_section(drive_case, scene.temperature_C);
  belt::LoadCycleOptions options() const {
    belt::LoadCycleOptions o;
    o.effects = scene::make_plan(scene).load_cycle;
    return o;
  }
};

// The cushion's shear amplitude the heat source reads (docs/thermal.md §1): √2 × the rms of σ12 about
// its mean over the cycle. Known answers: a sinusoid gives its amplitude whatever its mean and phase;
// a pulse of height h over a share φ of the period gives h √(2 φ (1 − φ)) (not h/2, the half range);
// the closing interval from the last sample back to the first counts; a constant gives 0.
TEST(SceneHeat, CushionShearAmplitudeIsTheRmsOfItsHistory) {
  const double T = 0.05;
  std::vector<fatigue::StressSample> sine, pulse;
  const int n = 2000;
  for (int k = 0; k < n; ++k) {  // the last sample one step before the period's end: the closing interval
    fatigue::StressSample q;
    q.t_s = 0.01 + T * k / n;
    q.s12_MPa = 0.3 + 0.7 * std::sin(2.0 * M_PI * k / n + 0.4);
    sine.push_back(q);
    q.s12_MPa = (k >= 300 && k < 800) ? -1.2 : 0.0;  // φ = 0.25, a step at both ends
    pulse.push_back(q);
  }
  EXPECT_NEAR(scene::detail::equivalent_amplitude(sine, T), 0.7, 1e-9);
  // The trapezoidal rule smears each step over one sample: φ(1 − φ) to within 1/n.
  EXPECT_NEAR(scene::detail::equivalent_amplitude(pulse, T), 1.2 * std::sqrt(2.0 * 0.25 * 0.75), 1.2 / n);
  for (auto& q : sine) q.s12_MPa = 0.3;
  EXPECT_NEAR(scene::detail::equivalent_amplitude(sine, T), 0.0, 1e-7);
  // Without cards the layer reads G = E/3 and G″ = G tan 8°: γ_a = τ_a/|G*| with τ_a of the beam
  // level's own mid-cushion history.
  const MediumBeam m;
  const auto &s = m.scene;
  const auto &d = m.drive_case;
  const auto &cycle = m.cycle;
  const auto &sec = m.section;
  double tau = 0.0, half_range = 0.0;
  for (const auto& p : fatigue::beam_stress_histories(cycle, d, sec))
    if (p.role == fatigue::Role::cushion) {
      tau = scene::detail::equivalent_amplitude(p.samples, cycle.cycle_time_s);
      double lo = HUGE_VAL, hi = -HUGE_VAL;
      for (const auto& q : p.samples) lo = std::min(lo, q.s12_MPa), hi = std::max(hi, q.s12_MPa);
      half_range = 0.5 * (hi - lo);
    }
  const belt::HeatSources h = scene::detail::heat_sources(s, d, cycle);
  const double G = sec.cushion_modulus_MPa / 3.0;
  ASSERT_EQ(h.layers.back().name, "cushion, shear");
  EXPECT_NEAR(h.layers.back().strain_amplitude, tau / std::hypot(G, G * std::tan(8.0 * M_PI / 180.0)), 1e-12);
  EXPECT_LT(tau, 0.5 * half_range);  // the friction shear is a pulse over the sliding arcs
}

// The stretch layers without cards (docs/thermal.md §1): the land's amplitude is the rms over its
// depth (3-point Gauss) of √2 × the rms about the mean of the beam level's ε22(d, t) over the cycle,
// computed here from the load cycle's samples with the trapezoidal rule in time (closing interval
// included), and its loss modulus is the plane-strain one, E′ tan 8° / (1 − ν²). A square pulse's
// rms amplitude exceeds its half range where it lasts for a large share of the cycle: the bending of
// the medium drive's wrap arcs reads above the half range at the gap bottom's depths.
TEST(SceneHeat, StretchLayersReadTheRmsAmplitudeAtThePlaneStrainModulus) {
  const MediumBeam m;
  const auto &s = m.scene;
  const auto &d = m.drive_case;
  const auto &cycle = m.cycle;
  const auto &sec = m.section;
  const double K_m = sec.manufactured_curvature_1_mm;
  auto amplitude = [&](double depth_mm, double* half_range) {  // √2 rms(ε22 − mean) and half the range
    double area = 0.0, sum = 0.0, sum2 = 0.0, lo = HUGE_VAL, hi = -HUGE_VAL;
    const std::size_t n = cycle.samples.size();
    auto e = [&](std::size_t k) {
      const auto& q = cycle.samples[k % n];
      return (1.0 + q.F_N / d.belt.c_N) * (1.0 - q.K_1_mm * depth_mm) / (1.0 - K_m * depth_mm) - 1.0;
    };
    for (std::size_t k = 0; k < n; ++k) {
      const double t1 = k + 1 < n ? cycle.samples[k + 1].t_s : cycle.samples[0].t_s + cycle.cycle_time_s;
      const double dt = t1 - cycle.samples[k].t_s, a = e(k), b = e(k + 1);
      area += dt, sum += 0.5 * dt * (a + b), sum2 += 0.5 * dt * (a * a + b * b);
      lo = std::min(lo, a), hi = std::max(hi, a);
    }
    if (half_range) *half_range = 0.5 * (hi - lo);
    return std::sqrt(2.0 * (sum2 / area - (sum / area) * (sum / area)));
  };
  const double d0 = sec.cushion_mm, d1 = sec.land_depth_mm;
  const double x[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double mean_square = 0.0;
  for (int k = 0; k < 3; ++k) mean_square += 0.5 * w[k] * std::pow(amplitude(0.5 * (d0 + d1) + 0.5 * (d1 - d0) * x[k], nullptr), 2);
  const belt::HeatSources h = scene::detail::heat_sources(s, d, cycle);
  ASSERT_EQ(h.layers.front().name, "bottom rubber, land");
  EXPECT_NEAR(h.layers.front().strain_amplitude / std::sqrt(mean_square), 1.0, 1e-12);
  const double plane = 1.0 / (1.0 - sec.poisson * sec.poisson);
  EXPECT_NEAR(h.layers.front().loss_modulus_MPa / (sec.bottom_modulus_MPa * std::tan(8.0 * M_PI / 180.0) * plane), 1.0,
              1e-12);
  double half = 0.0;
  EXPECT_GT(amplitude(sec.land_depth_mm, &half), 1.1 * half);  // the wrap arcs' pulse: 1.28x on this drive
}

// With the thesis cards at the beam level the cushion's shear, read stress-controlled on the hot card
// (γ = τ/|G*|) at its rms amplitude, settles on the light, medium and heavy drives, the temperature
// rising with torque (docs/thermal.md §5; with the half range it ran away on the heavy drive).
TEST(SceneHeat, ThesisCardsSettleOnTheReferenceDrives) {
  auto cards = [](const std::string& load) {
    auto s = drive(load, true);
    s.materials["bottom"] = FITLIB_SOURCE_DIR "/datasets/cards/material-1-true.json";
    s.materials["cushion"] = FITLIB_SOURCE_DIR "/datasets/cards/material-2-true.json";
    s.life = scene::LifeSpec{};
    s.life->fidelity = core::Fidelity::beam;
    return s;
  };
  double last = 25.0;
  for (const char* load : {"light", "medium", "heavy"}) {
    const auto s = cards(load);
    const auto r = scene::run_life(s);
    ASSERT_TRUE(r.heat) << load;
    EXPECT_GT(r.heat->temperature_C, last) << load;
    last = r.heat->temperature_C;
    // The layer's γ_a is the stress-controlled fixed point γ = τ_a/|G*(γ)| on the card at the belt's
    // temperature, τ_a the rms amplitude of the fixed point's own mid-cushion history.
    const double T = r.heat->temperature_C;
    double tau = 0.0;
    for (const auto& p : fatigue::beam_stress_histories(*r.cycle, *r.drive, fatigue::default_beam_section(*r.drive, T)))
      if (p.role == fatigue::Role::cushion) tau = scene::detail::equivalent_amplitude(p.samples, r.cycle->cycle_time_s);
    const double gamma = r.heat->sources.layers.back().strain_amplitude;
    const card::Card c = card::load_card(s.materials.at("cushion"));
    model::TestCondition at;
    at.mode = model::TestMode::shear, at.temperature_C = T, at.strain_amplitude = gamma;
    at.frequency_Hz = r.drive->belt_speed_mm_s / r.drive->geometry.belt_length_mm;
    const auto m = card::moduli_in_mode(*c.model(), c.values(), at, s.material_poisson_ratio);
    EXPECT_NEAR(gamma * std::hypot(m.storage, m.loss) / tau, 1.0, 1e-8) << load;
    EXPECT_NEAR(r.heat->sources.layers.back().loss_modulus_MPa / m.loss, 1.0, 1e-10) << load;
  }
}

// A card with scatter and covariance: the table and life.json carry B10/B50; two runs give the same bytes.
TEST(SceneHeat, DistributionWithHeatIsPrintedAndByteReproducible) {
  fatigue::FatigueCard c = fatigue::default_card();
  c.separation.scatter = fatigue::LifeScatter{"lognormal", 0.25, 10};
  c.separation.covariance = fatigue::LawCovariance{{{1e-3, 0.0, 0.0}, {0.0, 0.04, 0.0}, {0.0, 0.0, 1e-5}}};
  c.levels.clear();  // the beam run reads these modes, not the bundled card's beam-level laws
  const std::string path = fitlib_test::temp_dir() + "scatter-card.json";
  fatigue::save_card(path, c);
  auto s = drive("medium", true);
  s.life = scene::LifeSpec{};
  s.life->card = path;
  const auto a = scene::run_life(s), b = scene::run_life(s);
  const std::string ja = scene::life_json(s, a, false).dump(2), jb = scene::life_json(s, b, false).dump(2);
  EXPECT_EQ(ja, jb);
  ASSERT_EQ(a.life->distribution.size(), 1u);  // the radial crack's law states no scatter
  const auto& d = a.life->distribution[0];
  EXPECT_LT(d.b10.h, d.b50.h);
  EXPECT_EQ(d.b50.cycles, a.life->report.modes[1].life_cycles);
  const std::string text = scene::life_text(s, a);
  EXPECT_NE(text.find("B10"), std::string::npos) << text;
  EXPECT_NE(text.find("belt temperature:"), std::string::npos) << text;
  EXPECT_NE(ja.find("\"heat_buildup\""), std::string::npos);
  // life.json states the belt temperature, each source and loss and the fixed point's iterations (item 2).
  const auto h = scene::life_json(s, a, false)["heat_buildup"];
  EXPECT_EQ(h["belt_temperature_C"], a.heat->temperature_C);
  EXPECT_EQ(h["hysteresis_W"], a.heat->sources.hysteresis_W);
  EXPECT_EQ(h["friction_W"], a.heat->sources.friction_W);
  EXPECT_EQ(h["convection_W"], a.heat->convection_W);
  EXPECT_EQ(h["contact_W"], a.heat->contact_W);
  EXPECT_EQ(h["iterations"], a.heat->iterations);
  EXPECT_EQ(h["layers"].size(), a.heat->sources.layers.size());
  EXPECT_NE(text.find("fixed-point iterations"), std::string::npos) << text;
}

}  // namespace
