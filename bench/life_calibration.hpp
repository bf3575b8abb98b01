#pragma once
// bench_life's table of the level calibration (issue 33 item 3; docs/fatigue.md §4 "One life scale for
// every level"): the held-out drives of the bundled fatigue card's calibration
// (provenance.level_calibration.held_out_drives, scripts/calibrate-levels.sh) at every level with
// the card's constants for that level's stresses, each level's life against the complete level's
// of the same run, the governing modes' agreement and the time. `bench_life calibration` prints it
// alone. The beam level runs the bare drive (its default: no cards), the segment levels the drive
// with the thesis cards carrying their tables' data windows (so the complete level holds the damage
// at what the tests reached), 2 load cycles. Goals (issue 33): beam within x3, elastic within x1.5.
#include <cstdio>
#include <string>

#include "fitlib/core/timer.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

namespace bench_life {

struct LevelRun {
  double n1 = 0.0, n2 = 0.0, life = 0.0, seconds = 0.0;
  std::string governing, error;
};

inline LevelRun run_level(const std::string& drive_file, const std::string& level, const std::string& bottom,
                          const std::string& cushion) {
  using namespace fitlib;
  scene::Scene s = scene::load_scene(drive_file);
  s.outputs = {{"life", true}};
  if (level != "beam") {
    s.materials["bottom"] = bottom, s.materials["cushion"] = cushion;
    s.life = scene::LifeSpec{};
    s.life->fidelity = core::fidelity_from_string(level, "level"), s.life->cycles = 2;
  }
  LevelRun out;
  try {
    const core::Stopwatch watch;
    const scene::SceneResult r = scene::run_scene(s);
    out.seconds = level == "beam" ? core::seconds_per_call([&] { scene::run_scene(s); }) : watch.seconds();
    out.n1 = r.life->report.modes[0].life_cycles, out.n2 = r.life->report.modes[1].life_cycles;
    out.life = r.life->report.life_cycles, out.governing = r.life->report.governing;
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

// `drives`: the folder of the drive files; `bottom`, `cushion`: the windowed thesis cards.
inline void calibration_table(const std::string& drives, const std::string& bottom, const std::string& cushion) {
  using namespace fitlib;
  const fatigue::FatigueCard card = fatigue::default_card();
  const nlohmann::json& cal = card.provenance.at("level_calibration");
  std::printf("## Level calibration: held-out drives (bundled card, calibrated %s at fitlib %s on %zu drives; "
              "goals: beam within x3, elastic within x1.5 of the complete level, same governing mode)\n\n",
              cal.at("date").get<std::string>().c_str(), cal.at("fitlib_commit").get<std::string>().c_str(),
              cal.at("calibration_drives").size());
  for (const char* level : {"beam", "elastic"})
    std::printf("%s stress factors: radial crack %.4g, separation %.4g\n", level,
                cal.at(level).at("stress_factor").at("radial_crack").get<double>(),
                cal.at(level).at("stress_factor").at("separation").get<double>());
  std::printf("\n| drive | level | N1 radial crack | N2 separation | governing | life / complete | mode | time |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (const auto& item : cal.at("held_out_drives").items()) {
    const std::string file = drives + "/" + item.key() + ".toml";
    const LevelRun complete = run_level(file, "complete", bottom, cushion);
    for (const char* level : {"beam", "elastic", "complete"}) {
      const LevelRun r = std::string(level) == "complete" ? complete : run_level(file, level, bottom, cushion);
      if (!r.error.empty() || !complete.error.empty()) {
        std::printf("| %s | %s | failed: %.100s |\n", item.key().c_str(), level,
                    (r.error.empty() ? complete.error : r.error).c_str());
        continue;
      }
      std::printf("| %s | %s | %.4g | %.4g | %s | %.3g | %s | %.3g s |\n", item.key().c_str(), level, r.n1, r.n2,
                  r.governing.c_str(), r.life / complete.life, r.governing == complete.governing ? "same" : "differs",
                  r.seconds);
      std::fflush(stdout);
    }
  }
  std::printf("\n");
}

}  // namespace bench_life
