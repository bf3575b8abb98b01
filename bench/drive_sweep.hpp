#pragma once
// The 1000-drive sweep of the life benchmarks (bench_beam, bench_life): torque 2…50 N·m × 25,
// driver speed 1000…4000 rpm × 4, temperature 60…120 °C × 10 on one scene's drive.
#include <exception>
#include <string>

#include "fitlib/core/timer.hpp"
#include "fitlib/scene/scene.hpp"

struct SweepCounts {
  int done = 0, refused = 0, separation = 0;
  double seconds = 0.0;
};

// governing(scene) returns the governing mode of one drive; a throw counts as refused (the belt
// slips or lifts off: no load cycle).
template <typename F>
SweepCounts sweep_1000_drives(fitlib::scene::Scene s, F governing) {
  SweepCounts c;
  const fitlib::core::Stopwatch watch;
  for (int i = 0; i < 25; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 10; ++k) {
        s.torque_Nm = 2.0 + 2.0 * i;
        s.pulleys[0].speed_rpm = 1000.0 + 1000.0 * j;
        s.temperature_C = 60.0 + 60.0 * k / 9.0;
        try {
          const std::string mode = governing(s);
          ++c.done;
          c.separation += mode == "separation";
        } catch (const std::exception&) {
          ++c.refused;
        }
      }
  c.seconds = watch.seconds();
  return c;
}
