// The beam level on the bundled reference drives (issue 11 item 5; docs/fatigue.md §5): finite
// lives and a governing mode on every drive, and what the beam level says about the light →
// severe mode switch. Found: with the default section (no notch factor, k_t = 1) separation
// governs on all four drives; the mechanism of the switch is there (N2/N1 falls by orders of
// magnitude with load because n2 ≫ n1), and the switch appears for a gap notch factor between
// the two bounds printed here, which the segment FE has to supply.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fitlib/fatigue/beam_section.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

namespace fitlib {
namespace {

fatigue::LifeReport reference_drive_life(const std::string& load, double notch_factor = 1.0) {
  const scene::Scene s = scene::load_scene(std::string(FITLIB_SOURCE_DIR) +
                                           "/datasets/drives/ref-0500-" + load + ".toml");
  const belt::DriveCase drive = scene::make_drive(s, scene::resolve_stiffness(s));
  const belt::LoadCycle cycle = belt::compute_load_cycle(drive);
  fatigue::BeamSection section = fatigue::default_beam_section(drive, s.temperature_C);
  section.gap_stress_concentration = notch_factor;
  return fatigue::beam_life(cycle, drive, section, fatigue::default_card(), s.temperature_C);
}

TEST(BeamLifeDrives, FiniteLivesAndTheModeSwitchWindow) {
  const char* loads[] = {"light", "medium", "heavy", "severe"};
  double previous_ratio = 0.0;
  double n1[4], n2[4];
  for (int k = 0; k < 4; ++k) {
    const fatigue::LifeReport r = reference_drive_life(loads[k]);
    ASSERT_EQ(r.modes.size(), 2u);
    n1[k] = r.modes[0].life_cycles;
    n2[k] = r.modes[1].life_cycles;
    EXPECT_TRUE(std::isfinite(n1[k]) && n1[k] > 0.0) << loads[k];
    EXPECT_TRUE(std::isfinite(n2[k]) && n2[k] > 0.0) << loads[k];
    EXPECT_TRUE(std::isfinite(r.life_h)) << loads[k];
    EXPECT_NE(r.governing, "none");
    std::printf("%-7s N1 %.4g  N2 %.4g  governing %s (%.4g h)\n", loads[k], n1[k], n2[k],
                r.governing.c_str(), r.life_h);
    // Both lives fall with load, separation much faster (n2 ≫ n1).
    if (k > 0) {
      EXPECT_LT(n1[k], n1[k - 1]);
      EXPECT_LT(n2[k], n2[k - 1]);
      EXPECT_LT(n2[k] / n1[k], previous_ratio);
    }
    previous_ratio = n2[k] / n1[k];
    if (k == 3) std::printf("%s", fatigue::life_table(r).c_str());
  }
  // What the beam level finds with k_t = 1: separation everywhere (no switch).
  EXPECT_LT(n2[0], n1[0]);
  EXPECT_LT(n2[3], n1[3]);
  EXPECT_LT(n2[3] / n1[3], 1e-4 * n2[0] / n1[0]);
  // N1 ∝ k_t^(−n1) exactly (only σ22 at the free gap bottom): the switch window.
  const double lower = std::pow(n1[0] / n2[0], 1.0 / 4.423);
  const double upper = std::pow(n1[3] / n2[3], 1.0 / 4.423);
  std::printf("light → radial crack for k_t > %.3f; severe stays separation for k_t < %.3f\n",
              lower, upper);
  EXPECT_LT(lower, upper);
  const double inside = std::sqrt(lower * upper);
  EXPECT_EQ(reference_drive_life("light", inside).governing, "radial_crack");
  EXPECT_EQ(reference_drive_life("severe", inside).governing, "separation");
  EXPECT_NEAR(reference_drive_life("light", lower * 1.0001).modes[0].life_cycles / n2[0],
              std::pow(1.0001, -4.423), 1e-9);
}

}  // namespace
}  // namespace fitlib
