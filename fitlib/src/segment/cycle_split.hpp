#pragma once
// A history-free run's load cycle solved as two halves at once (docs/segment.md "Cost (reference)",
// docs/decisions.md "Segment: a history-free cycle solved in two halves"). Without history a state
// depends on its load alone, not on the path to it, so the second half can start from its own bend
// to the state at the split — a planned increment in a span, where no contact load acts on the
// segment — instead of from the first half's end. Each half runs on its own thread; the halves'
// histories are joined in path order, so the samples are the planned ones of the whole cycle.
#include <array>
#include <functional>
#include <vector>

#include "fitlib/segment/cycle.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/point_law.hpp"

namespace fitlib::segment::detail {

// One run of solve_cycles for a drive and knobs (cycle.cpp).
using CycleSolve = std::function<CycleResult(const CycleDrive&, const CycleKnobs&, const SolverKnobs&)>;

// The planned breakpoint (share of the cycle, cycle_breakpoints) nearest the cycle's middle, within
// its middle half, whose segment (± reach_mm) lies where the history has no side pressure; 0: none.
double split_share(const belt::LoadHistory& h, const std::vector<double>& breakpoints, double reach_mm);

// The one cycle of `one` (history-free, planned steps) in two halves where a planned increment lies
// in a span, the long belt's end profiles tabulated once for both; else in one piece. The halves are
// joined as one run's result: their counts added, their checks' largest kept, the second half's bend
// left out of the histories.
CycleResult solve_history_free_cycle(const CycleSolve& solve, const CogSection& section, const MeshKnobs& mesh_knobs,
                                     const std::array<const PlaneStrainLaw*, 2>& laws, const CycleDrive& drive,
                                     CycleKnobs one, const SolverKnobs& solver);

}  // namespace fitlib::segment::detail
