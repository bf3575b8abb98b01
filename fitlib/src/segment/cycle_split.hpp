#pragma once
// A history-free run's load cycle solved as two halves at once (docs/segment.md "Cost (reference)",
// docs/decisions.md "Segment: a history-free cycle solved in two halves"). Without history a state
// depends on its load alone, not on the path to it, so the second half can start from its own bend
// to the state at the split — a planned increment in a span, where no contact load acts on the
// segment — instead of from the first half's end. Each half runs on its own thread; the halves'
// histories are joined in path order, so the samples are the planned ones of the whole cycle.
#include <functional>
#include <vector>

#include "fitlib/segment/cycle.hpp"

namespace fitlib::segment::detail {

// One run of solve_cycles for a drive and knobs (cycle.cpp).
using CycleSolve = std::function<CycleResult(const CycleDrive&, const CycleKnobs&, const SolverKnobs&)>;

// The planned breakpoint (share of the cycle, cycle_breakpoints) nearest the cycle's middle, within
// its middle half, whose segment (± reach_mm) lies where the history has no side pressure; 0: none.
double split_share(const belt::LoadHistory& h, const std::vector<double>& breakpoints, double reach_mm);

// The one cycle of `one` (history-free, planned steps, the end profiles given) solved as the halves
// before and after `share`, each on one thread of the element loop, joined as one run's result: the
// halves' counts added, their checks' largest kept, the second half's bend left out of the histories.
CycleResult solve_split_cycle(const CycleSolve& solve, const CycleDrive& drive, const CycleKnobs& one,
                              const SolverKnobs& solver, const std::vector<double>& breakpoints, double share);

}  // namespace fitlib::segment::detail
