// Beam-level life benchmark (issue 11 item 5; plain main, prints its tables):
// 1. Per reference drive (datasets/drives/ref-0500-*.toml): wall time of the load cycle, of the
//    beam stresses + fatigue on it, and of both; target ≤ 5 ms per drive. Baseline: the load
//    cycle alone, measured in the same run.
// 2. A 1000-drive sweep (torque 2…50 N·m × 25, driver speed 1000…4000 rpm × 4, temperature
//    60…120 °C × 10): total time, and the pull–life diagram at 3000 rpm, 80 °C (life per mode
//    versus torque, like Report III Fig 3.3).
// 3. Knobs: the load cycle's sampling step (4 … 0.25 mm) → time and change of life per mode;
//    the crack sweep (0, ±25°, ±45°) and the peak threshold (10 %, 25 %, 50 %) → life change.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "drive_sweep.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/fatigue/beam_section.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

using namespace fitlib;
using core::seconds_per_call;

namespace {

scene::Scene reference(const std::string& load) {
  return scene::load_scene(std::string(FITLIB_SOURCE_DIR) + "/datasets/drives/ref-0500-" + load +
                           ".toml");
}

struct Run {
  belt::DriveCase drive;
  belt::LoadCycle cycle;
  fatigue::LifeReport life;
};

Run run(const scene::Scene& s, const belt::LoadCycleOptions& o = {},
        const fatigue::FatigueCard& card = fatigue::default_card(),
        const fatigue::PeakOptions& peaks = {}) {
  Run r;
  r.drive = scene::make_drive(s, scene::resolve_stiffness(s));
  r.cycle = belt::compute_load_cycle(r.drive, o);
  r.life = fatigue::beam_life(r.cycle, r.drive, fatigue::default_beam_section(r.drive, s.temperature_C),
                              card, s.temperature_C, peaks);
  return r;
}

double change(double x, double ref) { return std::isfinite(x) && std::isfinite(ref) ? x / ref - 1.0 : NAN; }

}  // namespace

int main() {
  std::printf("## 1. Time per drive (beam level)\n\n");
  std::printf("| drive | load cycle | beam + fatigue | both | N1 (cycles) | N2 (cycles) | governing |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const char* load : {"light", "medium", "heavy", "severe"}) {
    const scene::Scene s = reference(load);
    const Run r = run(s);
    const double t_cycle = seconds_per_call([&] { belt::compute_load_cycle(r.drive); });
    const fatigue::BeamSection sec = fatigue::default_beam_section(r.drive, s.temperature_C);
    const double t_beam = seconds_per_call([&] {
      fatigue::beam_life(r.cycle, r.drive, sec, fatigue::default_card(), s.temperature_C);
    });
    const double t_both = seconds_per_call([&] { run(s); });
    std::printf("| %s | %.3f ms | %.3f ms | %.3f ms | %.4g | %.4g | %s |\n", load, 1e3 * t_cycle,
                1e3 * t_beam, 1e3 * t_both, r.life.modes[0].life_cycles, r.life.modes[1].life_cycles,
                r.life.governing.c_str());
  }

  std::printf("\n## 2. Sweep of 1000 drives\n\n");
  scene::Scene s = reference("medium");
  const SweepCounts c = sweep_1000_drives(s, [](const scene::Scene& d) { return run(d).life.governing; });
  std::printf("1000 drives in %.3f s (%.3f ms per drive): %d computed, %d refused (belt slips), "
              "%d governed by separation\n", c.seconds, c.seconds, c.done, c.refused, c.separation);

  std::printf("\n### Pull–life diagram (3000 rpm, 80 °C; medium drive's pulleys and tension)\n\n");
  std::printf("| torque N·m | N1 radial crack (h) | N2 separation (h) | governing |\n|---|---|---|---|\n");
  s = reference("medium");
  for (double torque : {2.0, 5.0, 10.0, 15.0, 20.0, 30.0, 40.0, 45.0, 50.0}) {
    s.torque_Nm = torque;
    try {
      const Run r = run(s);
      std::printf("| %.0f | %.4g | %.4g | %s |\n", torque, r.life.modes[0].life_h,
                  r.life.modes[1].life_h, r.life.governing.c_str());
    } catch (const std::exception& e) {
      std::printf("| %.0f | — | — | refused: %s |\n", torque, e.what());
    }
  }

  std::printf("\n## 3. Knobs (heavy drive)\n\n");
  s = reference("heavy");
  belt::LoadCycleOptions fine;
  fine.step_mm = 0.125;
  const Run ref = run(s, fine);
  std::printf("Load-cycle step (reference 0.125 mm):\n\n| step mm | samples | time | ΔN1 | ΔN2 |\n|---|---|---|---|---|\n");
  for (double step : {8.0, 4.0, 2.0, 1.0, 0.5, 0.25}) {
    belt::LoadCycleOptions o;
    o.step_mm = step;
    const Run r = run(s, o);
    const double t = seconds_per_call([&] { run(s, o); }, 0.1);
    std::printf("| %.3g | %zu | %.3f ms | %+.2e | %+.2e |\n", step, r.cycle.samples.size(), 1e3 * t,
                change(r.life.modes[0].life_cycles, ref.life.modes[0].life_cycles),
                change(r.life.modes[1].life_cycles, ref.life.modes[1].life_cycles));
  }
  const Run base = run(s);
  std::printf("\nCrack sweep and peak threshold (default ±25°, 25 %%):\n\n| knob | ΔN1 | ΔN2 |\n|---|---|---|\n");
  for (double sweep : {0.0, 45.0}) {
    fatigue::FatigueCard card = fatigue::default_card();
    card.crack_sweep_deg = sweep;
    const Run r = run(s, {}, card);
    std::printf("| sweep ±%.0f° | %+.3f | %+.3f |\n", sweep,
                change(r.life.modes[0].life_cycles, base.life.modes[0].life_cycles),
                change(r.life.modes[1].life_cycles, base.life.modes[1].life_cycles));
  }
  for (double threshold : {0.10, 0.50}) {
    fatigue::PeakOptions p;
    p.threshold = threshold;
    const Run r = run(s, {}, fatigue::default_card(), p);
    std::printf("| threshold %.0f %% | %+.3f | %+.3f |\n", 100 * threshold,
                change(r.life.modes[0].life_cycles, base.life.modes[0].life_cycles),
                change(r.life.modes[1].life_cycles, base.life.modes[1].life_cycles));
  }
  return 0;
}
