// The beam level on the bundled reference drives (issue 11 item 5): finite lives, a governing
// mode, and what the beam level says about the light → severe mode switch (docs/fatigue.md §5).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fitlib/fatigue/beam_section.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

namespace fitlib {
namespace {

struct DriveLife {
  fatigue::LifeReport report;
};

fatigue::LifeReport reference_drive_life(const std::string& load) {
  const scene::Scene s =
      scene::load_scene(std::string(FITLIB_SOURCE_DIR) + "/datasets/drives/ref-0500-" + load + ".toml");
  const belt::DriveCase drive = scene::make_drive(s, scene::resolve_stiffness(s));
  const belt::LoadCycle cycle = belt::compute_load_cycle(drive);
  return fatigue::beam_life(cycle, drive, fatigue::default_beam_section(drive, s.temperature_C),
                            fatigue::default_card(), s.temperature_C);
}

TEST(BeamLifeDrives, PrintLives) {
  for (const char* load : {"light", "medium", "heavy", "severe"}) {
    const fatigue::LifeReport r = reference_drive_life(load);
    std::printf("%-7s governing %-13s", load, r.governing.c_str());
    for (const auto& m : r.modes)
      std::printf("  %s: N=%.4g h=%.4g peaks=%zu max=%.3f", fatigue::to_string(m.mode),
                  m.life_cycles, m.life_h, m.peaks.size(),
                  m.peaks.empty() ? 0.0 : m.peaks.front().stress_MPa);
    std::printf("\n");
  }
}

}  // namespace
}  // namespace fitlib
