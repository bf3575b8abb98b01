// Life from the segment FE on a bundled reference drive (issue 11 items 1–2): load cycle →
// segment (elastic materials, coarse mesh) → stress histories → life. Finite lives, a governing
// mode, the histories' roles, and the cost.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/fatigue/segment_life.hpp"
#include "fitlib/segment/point_law.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

namespace fitlib {
namespace {

model::MaterialPointPtr iso(double E, double nu) {
  const model::ModelPtr m = model::make_model("elastic-iso", nlohmann::json::object());
  return model::make_material_point(*m, {E, nu});
}

fatigue::SegmentLife reference_life(const std::string& load, int steps_per_cycle) {
  const scene::Scene s = scene::load_scene(std::string(FITLIB_SOURCE_DIR) + "/datasets/drives/ref-0500-" + load + ".toml");
  const belt::DriveCase drive = scene::make_drive(s, scene::resolve_stiffness(s));
  const belt::LoadCycle cycle = belt::compute_load_cycle(drive);
  fatigue::SegmentLifeSetup setup;  // the life's default mesh
  setup.cycle.cycles = 2;
  setup.cycle.steps_per_cycle = steps_per_cycle;
  setup.cycle.manufactured_radius_mm = drive.geometry.belt_length_mm / (2.0 * M_PI);
  setup.materials = {iso(20.0, 0.49), iso(8.0, 0.49)};
  setup.temperature_C = s.temperature_C;
  return fatigue::segment_life(cycle, drive, setup, fatigue::default_card());
}

}  // namespace

// fatigue.md §3's consequence to check: because n2 ≫ n1, raising the load switches the predicted
// mode from radial crack to separation. The segment (Report I's exploratory isotropic elastic
// materials, E 20/8 MPa, ν 0.49; the bundled drives, no constant tuned) shows it between the light
// and the severe reference drive.
TEST(SegmentLife, ModeSwitchesFromRadialCrackOnTheLightDriveToSeparationOnTheSevereDrive) {
  const fatigue::SegmentLife light = reference_life("light", 40), severe = reference_life("severe", 40);
  EXPECT_EQ(light.report.governing, "radial_crack");
  EXPECT_EQ(severe.report.governing, "separation");
  for (const auto* l : {&light, &severe}) {
    EXPECT_LT(l->run.equilibrium_error, 1e-6);
    for (const auto& m : l->report.modes) EXPECT_TRUE(std::isfinite(m.life_cycles) && m.life_cycles > 0.0);
  }
  // Separation's life falls much faster with load than the radial crack's (n2 ≫ n1).
  const double n1 = light.report.modes[0].life_cycles / severe.report.modes[0].life_cycles;
  const double n2 = light.report.modes[1].life_cycles / severe.report.modes[1].life_cycles;
  EXPECT_GT(n2, 10.0 * n1);
  std::printf("light N1 %.4g N2 %.4g; severe N1 %.4g N2 %.4g cycles\n", light.report.modes[0].life_cycles,
              light.report.modes[1].life_cycles, severe.report.modes[0].life_cycles, severe.report.modes[1].life_cycles);
}

// The cord line against the belt force (issue 11: "reaction forces of the cord line — their sum
// must match F"). The segment prescribes the cord line (Fritzson §5), so the belt force F is carried
// by the cord itself and is no unknown of the FE: in the spans (no contact load, one curvature over
// the segment) the cord line's reactions — the thesis's "additional reaction forces at the neutral
// layer" — vanish against F/B, and the left half's longitudinal balance is end face + cord
// reactions = rubber section force. Measured on the light drive (docs/segment.md "Cord-line reactions and the belt force").
TEST(SegmentLife, CordLineReactionsInTheSpansAreSmallAgainstTheBeltForce) {
  const scene::Scene s = scene::load_scene(std::string(FITLIB_SOURCE_DIR) + "/datasets/drives/ref-0500-light.toml");
  const belt::DriveCase drive = scene::make_drive(s, scene::resolve_stiffness(s));
  const belt::LoadCycle cycle = belt::compute_load_cycle(drive);
  fatigue::SegmentLifeSetup setup;  // the life's mesh
  setup.cycle.cycles = 1;
  setup.cycle.manufactured_radius_mm = drive.geometry.belt_length_mm / (2.0 * M_PI);
  setup.materials = {iso(20.0, 0.49), iso(8.0, 0.49)};
  setup.temperature_C = s.temperature_C;
  const segment::CycleResult r = fatigue::segment_run(cycle, drive, setup);
  int spans = 0;
  for (const auto& q : r.loads) {
    if (!q.span) continue;
    ++spans;
    EXPECT_GT(q.belt_force_N_mm, 0.0);
    // The rubber carries a few per cent of F/B at ε = F/c (measured 5.7–6.3 %); the cord the rest.
    EXPECT_GT(q.rubber_section_N_mm, 0.0);
    EXPECT_LT(q.rubber_section_N_mm, 0.1 * q.belt_force_N_mm);
  }
  std::printf("span cord share %.4g, section mismatch %.3g over %d increments\n", r.span_cord_share,
              r.span_section_mismatch, spans);
  EXPECT_GE(spans, 5);
  EXPECT_LT(r.span_cord_share, segment::EquilibriumBounds::span_cord_share);  // measured 3e-8: zero to the Newton tolerance
  EXPECT_LT(r.span_section_mismatch, segment::EquilibriumBounds::span_section_mismatch);  // measured 7e-14
  EXPECT_LT(r.equilibrium_error, 1e-6);
}

TEST(SegmentLife, ReferenceDriveGivesFiniteLivesFromTheSegment) {
  const scene::Scene s = scene::load_scene(std::string(FITLIB_SOURCE_DIR) + "/datasets/drives/ref-0500-light.toml");
  const belt::DriveCase drive = scene::make_drive(s, scene::resolve_stiffness(s));
  const belt::LoadCycle cycle = belt::compute_load_cycle(drive);
  fatigue::SegmentLifeSetup setup;
  setup.mesh.fine_size_mm = 1.0, setup.mesh.coarse_size_mm = 2.5, setup.mesh.central_pitches = 1.0;
  setup.mesh.end_pitches = 1.0, setup.mesh.cushion_rows = 1;
  setup.cycle.cycles = 2;
  setup.cycle.steps_per_cycle = 40;
  setup.cycle.manufactured_radius_mm = drive.geometry.belt_length_mm / (2.0 * M_PI);
  setup.materials = {iso(20.0, 0.49), iso(8.0, 0.49)};
  setup.temperature_C = s.temperature_C;
  const fatigue::SegmentLife life = fatigue::segment_life(cycle, drive, setup, fatigue::default_card());
  ASSERT_EQ(life.report.modes.size(), 2u);
  for (const auto& m : life.report.modes) EXPECT_TRUE(std::isfinite(m.life_cycles) && m.life_cycles > 0.0);
  EXPECT_NE(life.report.governing, "none");
  EXPECT_LT(life.run.equilibrium_error, 1e-6);
  const auto histories = fatigue::segment_point_histories(life.run);
  EXPECT_EQ(histories[0].role, fatigue::Role::bottom);   // gap bottom
  EXPECT_EQ(histories[1].role, fatigue::Role::cushion);  // mid-cushion
  std::printf("segment life (light, elastic, coarse): N1 %.4g, N2 %.4g cycles, governing %s; %d elements, "
              "%d increments, %d iterations, %.2f s\n",
              life.report.modes[0].life_cycles, life.report.modes[1].life_cycles, life.report.governing.c_str(),
              life.run.elements, life.run.increments, life.run.newton_iterations, life.wall_s);
}

// The complete level (the Fritzson cards' full model) on the medium drive, one cycle: the thesis
// cards fail 0.81 L round the belt (driver exit) with a residual stuck at one node; the same cards
// with the damage rate C_d lowered from 0.6 to its bound 1e-3 pass that stretch in equilibrium. The
// damage driver's amplitude memory (4.37) is what the Newton iteration cannot follow there
// (docs/segment.md "Cost", docs/decisions.md "Segment complete level").
TEST(SegmentLife, CompleteLevelPassesTheMediumDrivesExitOnlyWithSlowDamage) {
  const std::string root = FITLIB_SOURCE_DIR;
  const scene::Scene s = scene::load_scene(root + "/datasets/drives/ref-0500-medium.toml");
  const belt::DriveCase drive = scene::make_drive(s, scene::resolve_stiffness(s));
  const belt::LoadCycle cycle = belt::compute_load_cycle(drive);
  auto setup_with = [&](double c_d) {
    fatigue::SegmentLifeSetup setup;  // the life's mesh, 60 steps per cycle
    setup.cycle.cycles = 1;
    setup.cycle.manufactured_radius_mm = drive.geometry.belt_length_mm / (2.0 * M_PI);
    setup.temperature_C = s.temperature_C;
    segment::RoleMaterialOptions o;
    o.fidelity = segment::Fidelity::complete;
    o.temperature_C = s.temperature_C;
    const char* cards[2] = {"/datasets/cards/material-1-true.json", "/datasets/cards/material-2-true.json"};
    for (int k = 0; k < 2; ++k) {
      const card::Card c = card::load_card(root + cards[k]);
      const model::ModelPtr m = c.model();
      std::vector<double> values = c.values();
      for (std::size_t i = 0; i < values.size(); ++i)
        if (m->parameters()[i].name == "C_d" && c_d > 0.0) values[i] = c_d;
      setup.materials[k] = segment::role_point(*m, values, o);
    }
    return setup;
  };
  const fatigue::SegmentLife slow = fatigue::segment_life(cycle, drive, setup_with(1e-3), fatigue::default_card());
  EXPECT_LT(slow.run.equilibrium_error, 1e-6);
  for (const auto& m : slow.report.modes) EXPECT_TRUE(std::isfinite(m.life_cycles) && m.life_cycles > 0.0);
  try {
    fatigue::segment_life(cycle, drive, setup_with(0.0), fatigue::default_card());
    ADD_FAILURE() << "the thesis cards now pass the medium drive: update docs/segment.md and this test";
  } catch (const core::NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("largest residual at node"), std::string::npos) << what;
    EXPECT_EQ(what.find("inverted"), std::string::npos) << what;
  }
}

}  // namespace fitlib
