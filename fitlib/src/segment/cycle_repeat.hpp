#pragma once
// A history-free run's later load cycles as copies of its first (CycleStepping::repeat_history_free_cycle;
// docs/segment.md "Cost (reference)").
#include <array>

#include "fitlib/segment/cycle.hpp"

namespace fitlib::segment::detail {

// Whether every load cycle of the run starts from the same state: no law (role or element) carries
// state, no inertia (PhysicsOptions::inertia), no tangential flank law (its stick's slip, the
// sliding friction's velocity), the planned schedule (not given positions) over two or more cycles,
// and the knob on. The only memory left is Newton's start, so the cycles agree to its tolerance.
bool repeats_first_cycle(const std::array<const PlaneStrainLaw*, 2>& laws, const CycleKnobs& knobs,
                         const SolverKnobs& solver);

// `one`, a run of the bend and one cycle, extended to `cycles` cycles: each history's samples and
// each increment's load totals after the bend (t > period) copied once per later cycle, their time
// shifted by the period and their path position by the cycle's length `length_mm`.
void repeat_first_cycle(CycleResult& one, int cycles, double length_mm);

}  // namespace fitlib::segment::detail
