// A history-free run's load cycle solved as two halves at once (cycle_split.hpp).
#include "cycle_split.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <thread>

#include "cycle_parts.hpp"
#include "fitlib/core/error.hpp"

namespace fitlib::segment::detail {
namespace {

// No side pressure anywhere over [a, b] (the samples inside and the ends, linear between them).
bool free_of_contact(const belt::LoadHistory& h, double a, double b) {
  if (h.at_position(a).p_MPa > 0.0 || h.at_position(b).p_MPa > 0.0) return false;
  const double L = h.length_mm();
  for (const belt::LoadState& q : h.samples())
    for (double turn : {-L, 0.0, L})
      if (q.s_mm + turn > a && q.s_mm + turn < b && q.p_MPa > 0.0) return false;
  return true;
}

// The entries of a half's history after its bend (t beyond one period), moved to the whole cycle's
// path and time.
template <class Entry>
void append_after_bend(std::vector<Entry>& into, const std::vector<Entry>& from, double period_s, double s_mm,
                       double t_s) {
  for (Entry e : from)
    if (e.t_s > period_s) {
      e.s_mm += s_mm, e.t_s += t_s;
      into.push_back(e);
    }
}

CycleResult joined(CycleResult first, CycleResult second, double split_mm, double split_s) {
  const double period = first.cycle_time_s;
  for (auto [a, b] : {std::pair{&first.points, &second.points}, std::pair{&first.scanned, &second.scanned},
                      std::pair{&first.element_means, &second.element_means}})
    for (std::size_t k = 0; k < a->size(); ++k) append_after_bend((*a)[k].samples, (*b)[k].samples, period, split_mm, split_s);
  append_after_bend(first.loads, second.loads, period, split_mm, split_s);
  for (auto [a, b] : {std::pair{&first.equilibrium_error, second.equilibrium_error},
                      std::pair{&first.max_cord_reaction_N_mm, second.max_cord_reaction_N_mm},
                      std::pair{&first.span_cord_share, second.span_cord_share},
                      std::pair{&first.span_section_mismatch, second.span_section_mismatch}})
    *a = std::max(*a, b);
  for (int role = 0; role < 2; ++role) first.dissipation_J_mm[role] += second.dissipation_J_mm[role];
  first.increments += second.increments, first.newton_iterations += second.newton_iterations;
  first.factorizations += second.factorizations, first.cuts += second.cuts;
  first.final_state = std::move(second.final_state);
  flank_shares(first);
  return first;
}

}  // namespace

double split_share(const belt::LoadHistory& h, const std::vector<double>& breakpoints, double reach_mm) {
  const double L = h.length_mm();
  double best = 0.0;
  for (double b : breakpoints)
    if (b >= 0.25 && b <= 0.75 && std::abs(b - 0.5) < std::abs(best - 0.5) &&
        free_of_contact(h, b * L - reach_mm, b * L + reach_mm))
      best = b;
  return best;
}

namespace {

// The halves before and after `share` (of the cycle), each on one thread of the element loop.
CycleResult solve_in_halves(const CycleSolve& solve, const CycleDrive& drive, const CycleKnobs& one,
                            const SolverKnobs& solver, const std::vector<double>& breakpoints, double share) {
  const double L = drive.history->length_mm(), split_mm = share * L;
  CycleKnobs first = one, second = one;
  for (double b : breakpoints) {
    if (b <= share) first.stepping.positions_mm.push_back(b * L);
    else second.stepping.positions_mm.push_back((b - share) * L);
  }
  // The second half on the history seen from the split, its end profiles moved with it.
  const belt::LoadHistory from_split = drive.history->shifted(split_mm);
  CycleDrive second_drive = drive;
  second_drive.history = &from_split;
  for (CyclePhysics::EndProfile* f : {&second.physics.end_warping_mm, &second.physics.end_shear_MPa})
    if (*f) *f = [g = *f, split_mm](int side, double depth_mm, double s_mm) { return g(side, depth_mm, s_mm + split_mm); };
  second.outputs.progress = nullptr;
  SolverKnobs one_thread = solver;
  one_thread.threads = 1;
  one_thread.newton.split_factorisation = false;  // each half has its core already: one LDLᵀ each
  CycleResult a, b;
  std::exception_ptr failed;
  auto second_half = [&] {
    try {
      b = solve(second_drive, second, one_thread);
    } catch (...) {
      failed = std::current_exception();
    }
  };
  try {
    std::thread worker;
    if (solver_threads(solver) > 1) worker = std::thread(second_half);
    try {
      a = solve(drive, first, one_thread);
    } catch (...) {
      if (worker.joinable()) worker.join();
      throw;
    }
    if (worker.joinable()) worker.join();
    else second_half();
    if (failed) std::rethrow_exception(failed);
  } catch (const core::NumericalError&) {
    // A half that fails (its own bend to the split's state included) says nothing the whole cycle
    // would: the cycle is solved in one piece for its result or its own message.
    return solve(drive, one, solver);
  }
  const double split_s = share * a.cycle_time_s;
  return joined(std::move(a), std::move(b), split_mm, split_s);
}

}  // namespace

CycleResult solve_history_free_cycle(const CycleSolve& solve, const CogSection& section, const MeshKnobs& mesh_knobs,
                                     const std::array<const PlaneStrainLaw*, 2>& laws, const CycleDrive& drive,
                                     CycleKnobs one, const SolverKnobs& solver) {
  const Mesh straight = build_mesh(section, mesh_knobs);
  const std::vector<double> breakpoints =
      cycle_breakpoints(*drive.history, one.stepping.steps_per_cycle, one.stepping.change_weight, straight.half_length_mm);
  const double share = split_share(*drive.history, breakpoints, 1.5 * straight.half_length_mm);
  if (!(share > 0.0)) return solve(drive, one, solver);
  CyclePhysics& physics = one.physics;
  if (physics.ends == EndCondition::sheared && !physics.end_warping_mm && !physics.end_shear_MPa)
    long_belt_ends(section, straight, laws, drive, physics.end_warping_mm, physics.end_shear_MPa);
  return solve_in_halves(solve, drive, one, solver, breakpoints, share);
}

}  // namespace fitlib::segment::detail
