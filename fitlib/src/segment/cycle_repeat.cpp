// A history-free run's later load cycles as copies of its first (cycle_repeat.hpp).
#include "cycle_repeat.hpp"

#include <vector>

namespace fitlib::segment::detail {

bool repeats_first_cycle(const std::array<const PlaneStrainLaw*, 2>& laws, const CycleKnobs& knobs,
                         const SolverKnobs& solver) {
  // (element_laws carry no state: run_cycle refuses one that does.)
  const bool stateless = laws[0]->state_size() == 0 && laws[1]->state_size() == 0;
  return knobs.stepping.repeat_history_free_cycle && stateless && !solver.physics.inertia &&
         !knobs.physics.flank_along_belt() &&
         knobs.stepping.positions_mm.empty() && knobs.stepping.cycles >= 2;
}

namespace {

// The entries after the bend (time > the period), copied `cycles` − 1 times, shifted per cycle.
template <class Entry>
void repeat(std::vector<Entry>& entries, int cycles, double period_s, double length_mm) {
  std::vector<Entry> first;
  for (const Entry& e : entries)
    if (e.t_s > period_s) first.push_back(e);
  for (int c = 1; c < cycles; ++c)
    for (Entry e : first) {
      e.t_s += c * period_s, e.s_mm += c * length_mm;
      entries.push_back(e);
    }
}

}  // namespace

void repeat_first_cycle(CycleResult& one, int cycles, double length_mm) {
  const double period = one.cycle_time_s;
  for (auto* histories : {&one.points, &one.scanned, &one.element_means})
    for (MonitoredHistory& h : *histories) repeat(h.samples, cycles, period, length_mm);
  repeat(one.loads, cycles, period, length_mm);
}

}  // namespace fitlib::segment::detail
