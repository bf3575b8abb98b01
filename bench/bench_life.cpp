// Life accuracy versus time per fidelity level (issue 11 item 5; plain main, prints its tables):
// 1. For every bundled reference drive (datasets/drives/ref-0500-*.toml) and every fidelity level
//    of [life] (kLevels): life per mode, governing mode, wall time of the whole scene run (mean
//    of repeated runs) and of its stress and fatigue effects. A level this build cannot run is
//    printed with the planner's reason; it gets numbers as soon as the planner can run it.
// 2. The beam level's 1000-drive sweep through the planner (torque 2…50 N·m × 25, driver speed
//    1000…4000 rpm × 4, temperature 60…120 °C × 10): total time, drives refused (belt slips).
#include <cstdio>
#include <string>
#include <vector>

#include "drive_sweep.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

using namespace fitlib;

namespace {

const std::vector<std::string> kLevels = {"beam", "elastic", "complete"};  // one line per level

scene::Scene reference(const std::string& load, const std::string& fidelity) {
  auto s = scene::load_scene(std::string(FITLIB_SOURCE_DIR) + "/datasets/drives/ref-0500-" + load + ".toml");
  s.outputs = {{"life", true}};
  s.life = scene::LifeSpec{};
  s.life->fidelity = fidelity;
  return s;
}

double effect_ms(const scene::SceneResult& r, const std::string& name) {
  for (const auto& e : r.plan.effects)
    if (e.name == name) return 1e3 * e.wall_s;
  return 0.0;
}

std::string reason_not_run(const scene::SceneResult& r) {
  for (const auto& e : r.plan.effects)
    if (e.name == "fatigue") return e.reason;
  return "?";
}

void level_table() {
  std::printf("## 1. Life per fidelity level\n\n");
  std::printf("| drive | fidelity | N1 radial crack (cycles) | N2 separation (cycles) | governing | life (h) "
              "| scene run | stresses | fatigue |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const char* load : {"light", "medium", "heavy", "severe"})
    for (const auto& level : kLevels) {
      const scene::Scene s = reference(load, level);
      const scene::SceneResult r = scene::run_scene(s);
      if (!r.life) {
        std::printf("| %s | %s | — | — | — | — | — | — | %s |\n", load, level.c_str(), reason_not_run(r).c_str());
        continue;
      }
      const double t_run = core::seconds_per_call([&] { scene::run_scene(s); });
      const auto& m = r.life->report.modes;
      std::printf("| %s | %s | %.4g | %.4g | %s | %.4g | %.3f ms | %.3f ms | %.3f ms |\n", load, level.c_str(),
                  m[0].life_cycles, m[1].life_cycles, r.life->report.governing.c_str(), r.life->report.life_h,
                  1e3 * t_run, effect_ms(r, level == "beam" ? "beam_stresses" : "segment_fe"),
                  effect_ms(r, "fatigue"));
    }
}

void beam_sweep() {
  std::printf("\n## 2. Beam level: sweep of 1000 drives through the planner\n\n");
  const SweepCounts c = sweep_1000_drives(reference("medium", "beam"), [](const scene::Scene& s) {
    return scene::run_scene(s).life->report.governing;
  });
  std::printf("1000 drives in %.3f s (%.3f ms per drive): %d computed, %d refused (belt slips), "
              "%d governed by separation\n", c.seconds, c.seconds, c.done, c.refused, c.separation);
}

}  // namespace

int main() {
  level_table();
  beam_sweep();
  return 0;
}
