#include "fitlib/fit/fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "admissible.hpp"
#include "backends.hpp"
#include "quality.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/fit/problem.hpp"
#include "fitlib/fit/staged.hpp"
#include "fitlib/core/enum_names.hpp"

namespace fitlib::fit {

namespace {
constexpr core::EnumName<Backend> kBackendNames[] = {{Backend::automatic, "auto"}, {Backend::nnls, "nnls"},
                                                    {Backend::ceres, "ceres"},    {Backend::nlopt, "nlopt"},
                                                    {Backend::staged, "staged"},  {Backend::automatic, "automatic"}};
constexpr core::EnumName<ResidualKind> kResidualNames[] = {
    {ResidualKind::log10, "log10"}, {ResidualKind::relative, "relative"}, {ResidualKind::complex, "complex"},
    {ResidualKind::log10, "log"}};
}  // namespace

Backend parse_backend(const std::string& text) { return core::parse_enum(kBackendNames, text, "backend"); }
const char* to_string(Backend backend) { return core::enum_name(kBackendNames, backend); }

ResidualKind parse_residual_kind(const std::string& text) {
  return core::parse_enum(kResidualNames, text, "residual kind");
}
const char* to_string(ResidualKind kind) { return core::enum_name(kResidualNames, kind); }

model::DataSummary summarize(const data::DynamicTestTable& table) {
  model::DataSummary s;
  if (table.rows.empty()) return s;
  constexpr double inf = std::numeric_limits<double>::infinity();
  s.omega_min_rad_s = s.storage_min_MPa = s.temperature_min_C = inf;
  s.omega_max_rad_s = s.storage_max_MPa = s.temperature_max_C = -inf;
  s.loss_max_MPa = 0.0;
  // Bulk rows (K, orders of magnitude above the deviatoric moduli and without a loss peak) would
  // stretch the ranges a start is placed from; they count only in an all-bulk table.
  bool all_bulk = true;
  for (const auto& row : table.rows)
    all_bulk = all_bulk && row.condition.mode == model::TestMode::bulk;
  for (const auto& row : table.rows) {
    if (!all_bulk && row.condition.mode == model::TestMode::bulk) continue;
    const double omega = core::angular_frequency(row.condition.frequency_Hz);
    s.omega_min_rad_s = std::min(s.omega_min_rad_s, omega);
    s.omega_max_rad_s = std::max(s.omega_max_rad_s, omega);
    s.storage_min_MPa = std::min(s.storage_min_MPa, row.storage_MPa);
    s.storage_max_MPa = std::max(s.storage_max_MPa, row.storage_MPa);
    s.loss_max_MPa = std::max(s.loss_max_MPa, row.loss_MPa);
    if (row.condition.has_temperature()) {
      s.temperature_min_C = std::min(s.temperature_min_C, row.condition.temperature_C);
      s.temperature_max_C = std::max(s.temperature_max_C, row.condition.temperature_C);
    }
  }
  if (!std::isfinite(s.temperature_min_C)) s.temperature_min_C = s.temperature_max_C = 23.0;
  return s;
}

namespace {

using detail::movable;
using detail::StageOutcome;

std::string describe_objective(const FitOptions& o) {
  std::ostringstream s;
  s << (o.residual == ResidualKind::log10      ? "sum of squared log10 errors"
        : o.residual == ResidualKind::relative ? "sum of squared relative errors"
                                               : "sum of squared errors relative to |E*| of the row")
    << " of storage, loss and mean moduli; weights storage " << o.storage_weight << ", loss "
    << o.loss_weight << ", mean " << o.mean_weight
    << " (mean only where measured), times per-row weights; loss with tan delta < 1e-6 as an "
       "absolute error on the storage scale";
  return s.str();
}

void note(FitResult& result, const std::string& prefix, const StageOutcome& outcome) {
  if (!outcome.note.empty()) result.messages.push_back(prefix + outcome.note);
}

std::vector<int> all_free(const Problem& problem) {
  std::vector<int> out;
  for (int i = 0; i < problem.num_parameters(); ++i)
    if (!problem.user_fixed()[i]) out.push_back(i);
  return out;
}

bool has_free_nonlinear(const Problem& problem) {
  for (int i : all_free(problem))
    if (!problem.specs()[i].linear) return true;
  return false;
}

// A model with at most one series term and at most this many free non-linear parameters (zener3,
// fractional-zener, with or without a temperature law's two constants) gets the automatic
// backend's multistart check: ~0.1 s for 200 rows, where a single Ceres descent can stop in a
// basin ten times worse (docs/fitting.md "Backends").
constexpr int kGlobalCheckMaxNonlinear = 4;

bool wants_global_check(const Problem& problem) {
  if (detail::series_terms(problem.specs()).times.size() > 1) return false;
  int nonlinear = 0;
  for (int i : all_free(problem)) nonlinear += !problem.specs()[i].linear;
  return nonlinear > 0 && nonlinear <= kGlobalCheckMaxNonlinear;
}

bool has_free_linear(const Problem& problem) {
  for (int i : all_free(problem))
    if (problem.specs()[i].linear) return true;
  return false;
}

// Linear solve with the non-linear parameters held; then (polish) the positive linear
// parameters on the exact objective in log space.
StageOutcome linear_stage(Problem& problem, FitResult& result, bool polish) {
  problem.set_free(all_free(problem));
  StageOutcome out;
  out.converged = true;
  if (problem.options().linear_start) {
    out = detail::run_nnls(problem);
    note(result, "", out);
  }
  if (!polish) return out;
  std::vector<int> linear;
  for (int i : all_free(problem))
    if (problem.specs()[i].linear) linear.push_back(i);
  problem.set_free(movable(problem, linear));
  const std::vector<double> before = problem.natural();
  const double cost_before = problem.cost(before);
  StageOutcome polished = detail::run_ceres(problem, problem.options().max_iterations);
  if (!(problem.cost(problem.natural()) <= cost_before)) problem.natural() = before;
  note(result, "polish ", polished);
  polished.converged = polished.converged && out.converged;
  return polished;
}

// Before a free-τ stage: moduli the NNLS start left at exactly 0 would stay there in log space
// (and their τ would have no effect); restart them at 1e-3 × the mean positive modulus.
void revive_zero_moduli(Problem& problem, FitResult& result) {
  std::vector<double>& p = problem.natural();
  double sum = 0.0;
  int positive = 0;
  std::vector<int> zeros;
  for (int i : all_free(problem)) {
    if (!problem.specs()[i].linear || !problem.is_log(i)) continue;
    if (p[i] > 0.0) {
      sum += p[i];
      ++positive;
    } else {
      zeros.push_back(i);
    }
  }
  if (zeros.empty() || positive == 0) return;
  const double restart = 1e-3 * sum / positive;
  for (int i : zeros) p[i] = std::max(restart, problem.lower(i) > 0.0 ? problem.lower(i) * 1.01 : 0.0);
  result.messages.push_back("nnls start: " + std::to_string(zeros.size()) +
                            " zero moduli restarted at 1e-3 x the mean modulus for the free stage");
}

// The local descent the options name (FitOptions::descent).
StageOutcome local_descent(Problem& problem, int max_iterations) {
  return problem.options().descent == LocalDescent::normal_equations
             ? detail::run_levenberg_marquardt(problem, max_iterations)
             : detail::run_ceres(problem, max_iterations);
}

StageOutcome ceres_stage(Problem& problem, FitResult& result) {
  problem.set_free(movable(problem, all_free(problem)));
  StageOutcome out = local_descent(problem, problem.options().max_iterations);
  note(result, "", out);
  return out;
}

StageOutcome nlopt_stage(Problem& problem, FitResult& result, int starts, int max_iterations) {
  problem.set_free(movable(problem, all_free(problem)));
  StageOutcome out = detail::run_nlopt(problem, starts, max_iterations);
  note(result, "", out);
  return out;
}

// Ceres; when it fails (no usable solution, or no decrease from the start) an NLopt
// multistart from the same start and a Ceres finish, keeping the better of the two. Reaching
// the iteration limit with a lower cost is not a failure (converged = false, said so).
StageOutcome ceres_with_fallback(Problem& problem, FitResult& result, std::string& used) {
  const std::vector<double> start = problem.natural();
  const double start_cost = problem.cost(start);
  StageOutcome out;
  bool usable = false;
  try {
    out = ceres_stage(problem, result);
    usable = out.usable;
  } catch (const core::NumericalError& e) {
    result.messages.push_back(std::string("ceres failed: ") + e.what());
  }
  const double ceres_cost = usable ? problem.cost(problem.natural()) : start_cost;
  if (usable && (ceres_cost < start_cost || out.converged)) return out;
  const std::vector<double> ceres_point = usable ? problem.natural() : start;
  problem.natural() = start;
  result.messages.push_back("auto: ceres failed; trying an nlopt multistart");
  nlopt_stage(problem, result, problem.options().multistart, problem.options().max_iterations);
  StageOutcome finish = ceres_stage(problem, result);
  if (problem.cost(problem.natural()) <= ceres_cost) {
    used += "+nlopt+ceres";
    return finish;
  }
  problem.natural() = ceres_point;
  return out;
}

// The multistart check of a small model (wants_global_check): an NLopt multistart and
// a Ceres finish from the same start as the local descent; the lower cost is kept, and said.
StageOutcome keep_global_if_lower(Problem& problem, FitResult& result, const std::vector<double>& start,
                                  StageOutcome local, std::string& used) {
  const std::vector<double> local_point = problem.natural();
  const double local_cost = problem.cost(local_point);
  problem.natural() = start;
  nlopt_stage(problem, result, problem.options().multistart, problem.options().max_iterations);
  StageOutcome global = ceres_stage(problem, result);
  const double global_cost = problem.cost(problem.natural());
  if (global.usable && global_cost < local_cost * (1.0 - 1e-9)) {
    std::ostringstream s;
    s << "auto: the multistart check found a lower cost than the local descent (" << local_cost << " -> "
      << global_cost << "); kept";
    result.messages.push_back(s.str());
    used += "+nlopt+ceres";
    return global;
  }
  problem.natural() = local_point;
  return local;
}

StageOutcome run_stages(Problem& problem, FitResult& result, const Schedule& schedule) {
  const core::Stopwatch clock;
  const FitOptions& o = problem.options();
  StageOutcome last;
  for (std::size_t s = 0; s < schedule.stages.size(); ++s) {
    const Stage& st = schedule.stages[s];
    const std::string key = "stages[" + std::to_string(s) + "]";
    std::vector<int> chosen = select_parameters(problem.specs(), st.free, key + ".free");
    if (!st.lock.empty()) {
      const std::vector<int> locked = select_parameters(problem.specs(), st.lock, key + ".lock");
      chosen.erase(std::remove_if(chosen.begin(), chosen.end(),
                                  [&](int i) {
                                    return std::find(locked.begin(), locked.end(), i) !=
                                           locked.end();
                                  }),
                   chosen.end());
    }
    problem.set_free(movable(problem, chosen));
    const int iterations = st.max_iterations > 0 ? st.max_iterations : o.max_iterations;
    if (st.backend == "nnls") last = detail::run_nnls(problem);
    else if (st.backend == "nlopt")
      last = detail::run_nlopt(problem, st.multistart > 0 ? st.multistart : o.multistart,
                               iterations);
    else last = detail::run_ceres(problem, iterations);
    // Accuracy and time reached after each stage: what a user tunes a schedule by.
    FitMetrics reached;
    problem.measure(problem.natural(), reached);
    std::ostringstream reached_note;
    reached_note << "; mean relative error " << 100.0 * reached.mean_rel_error << " %";
    if (o.record_timing) reached_note << " after " << clock.seconds() << " s";
    last.note += reached_note.str();
    note(result, "stage '" + st.name + "': ", last);
  }
  return last;
}

StageOutcome run_schedule(Problem& problem, FitResult& result) {
  const std::string& path = problem.options().schedule_path;
  const Schedule schedule = path.empty() ? default_schedule() : load_schedule(path);
  try {
    return run_stages(problem, result, schedule);
  } catch (const core::InputError& e) {  // a selector that selects nothing: name the schedule file
    if (!e.file().empty()) throw;
    throw core::InputError(e.detail(), path.empty() ? "the default schedule" : path, 0, 0, e.key());
  }
}

// Series terms (a "viscous" modulus paired with a "time" constant, in the same order) are
// exchangeable: a fit may return them in any order. Sort them by time constant so that cards
// read naturally, and keep the sorted vector only if the cost is unchanged (the permutation is
// then the same model).
void sort_series_terms(Problem& problem, FitResult& result) {
  std::vector<int> moduli, times;
  for (int i = 0; i < problem.num_parameters(); ++i) {
    if (problem.specs()[i].group == "viscous") moduli.push_back(i);
    if (problem.specs()[i].group == "time") times.push_back(i);
  }
  if (moduli.size() != times.size() || times.size() < 2) return;
  for (std::size_t k = 0; k < times.size(); ++k)
    if (problem.user_fixed()[times[k]] || problem.user_fixed()[moduli[k]]) return;
  std::vector<double>& p = problem.natural();
  std::vector<std::size_t> order(times.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return p[times[a]] < p[times[b]]; });
  bool identity = true;
  for (std::size_t k = 0; k < order.size(); ++k) identity = identity && order[k] == k;
  if (identity) return;
  std::vector<double> sorted = p;
  for (std::size_t k = 0; k < order.size(); ++k) {
    sorted[times[k]] = p[times[order[k]]];
    sorted[moduli[k]] = p[moduli[order[k]]];
  }
  const double before = problem.cost(p), after = problem.cost(sorted);
  if (!(std::abs(after - before) <= 1e-10 * (before + 1e-300))) return;
  p = sorted;
  result.messages.push_back("series terms sorted by time constant (same model, same cost)");
}

// Bounds of the admissible window at the start (docs/fitting.md "Admissible terms").
void admit_start(Problem& problem, FitResult& result) {
  result.admissible = detail::admissible_window(problem, problem.natural());
  const AdmissibleWindow& w = result.admissible;
  if (!w.applies) return;
  const int moved = detail::apply_admissible_bounds(problem, w);
  result.messages.push_back(detail::describe_window(w, moved));
}

constexpr int kRepolishIterations = 100;

// Re-solves the current free set after bounds or terms changed: the linear polish for the
// nnls backend, Ceres otherwise.
void repolish(Problem& problem, FitResult& result, bool linear_only) {
  std::vector<int> free = all_free(problem);
  if (linear_only)
    free.erase(std::remove_if(free.begin(), free.end(), [&](int i) { return !problem.specs()[i].linear; }),
               free.end());
  problem.set_free(detail::movable(problem, free));
  if (problem.num_free() == 0) return;
  const std::vector<double> before = problem.natural();
  // A re-polish starts next to a solution: a capped budget (the merge check judges the result).
  const detail::StageOutcome out =
      local_descent(problem, std::min(problem.options().max_iterations, kRepolishIterations));
  if (!out.usable || !std::isfinite(problem.cost(problem.natural()))) problem.natural() = before;
  note(result, "re-polish ", out);
}

// With a temperature law the window moves with the fitted shift: re-bound and re-solve until the
// terms lie in the window of the fitted law (at most 3 rounds, then the window of the last law).
void readmit(Problem& problem, FitResult& result, bool linear_only) {
  if (!result.admissible.applies) return;
  for (int round = 0; round < 3; ++round) {
    const AdmissibleWindow w = detail::admissible_window(problem, problem.natural());
    if (!w.applies) return;
    const bool same = std::abs(std::log(w.tau_min_s / result.admissible.tau_min_s)) < 1e-9 &&
                      std::abs(std::log(w.tau_max_s / result.admissible.tau_max_s)) < 1e-9;
    result.admissible = w;
    if (detail::apply_admissible_bounds(problem, w) == 0 || same) return;
    result.messages.push_back("admissible terms: window moved with the fitted temperature law to [" +
                              core::format_number(w.tau_min_s) + ", " + core::format_number(w.tau_max_s) +
                              "] s; terms moved inside and the fit re-polished");
    repolish(problem, result, linear_only);
  }
}

// A merge is kept when the re-polished cost is within this factor of the cost before it.
constexpr double kMergeCostSlack = 1.001;

// Series terms the identifiability report flags are merged into the active term with the nearest
// time constant (moduli summed, time constants averaged in log weighted by modulus) and the fit
// re-polished; never kept silently. Returns true when something was merged.
bool merge_unidentifiable_terms(Problem& problem, FitResult& result, bool linear_only) {
  const detail::SeriesTerms series = detail::series_terms(problem.specs());
  const auto& flagged = result.identifiability.not_identifiable;
  auto is_flagged = [&](int i) {
    return std::find(flagged.begin(), flagged.end(), problem.specs()[i].name) != flagged.end();
  };
  std::vector<double>& p = problem.natural();
  const std::vector<double> before = p;
  const double cost_before = problem.cost(before);
  std::vector<bool> received(series.times.size(), false);
  std::string merged;
  for (std::size_t k = 0; k < series.times.size(); ++k) {
    const int mk = series.moduli[k], tk = series.times[k];
    // Only a linear modulus may be 0 (a removed term); compliances and the like stay, flagged.
    if (!problem.specs()[mk].linear || p[mk] == 0.0 || !(is_flagged(mk) || is_flagged(tk)) ||
        problem.user_fixed()[mk])
      continue;
    if (received[k]) continue;  // merged into this round: no chains
    // The nearest active term (pairs per round; the next round sees the merged fit).
    int best = -1;
    double distance = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < series.times.size(); ++j) {
      const double d = std::abs(std::log(p[series.times[j]] / p[tk]));
      if (j != k && p[series.moduli[j]] > 0.0 && d < distance) {
        distance = d;
        best = static_cast<int>(j);
      }
    }
    if (best >= 0) received[best] = true;
    if (best < 0) continue;
    const int mj = series.moduli[best], tj = series.times[best];
    if (!linear_only && !problem.user_fixed()[tj])
      p[tj] = std::exp((p[mj] * std::log(p[tj]) + p[mk] * std::log(p[tk])) / (p[mj] + p[mk]));
    p[mj] = std::min(p[mj] + p[mk], problem.upper(mj));
    p[mk] = 0.0;
    merged += (merged.empty() ? "" : ", ") + problem.specs()[mk].name + " into " + problem.specs()[mj].name;
  }
  if (merged.empty()) return false;
  repolish(problem, result, linear_only);
  const double after = problem.cost(problem.natural());
  // Absolute slack: an exact fit's cost is rounding noise (rms residual below 1e-5).
  if (!(after <= kMergeCostSlack * cost_before + 1e-10 * problem.num_residuals())) {
    problem.natural() = before;
    std::ostringstream s;
    s << "terms the data cannot identify kept: merging them (" << merged << ") raised the cost x"
      << after / cost_before;
    result.messages.push_back(s.str());
    return false;
  }
  result.messages.push_back("terms the data cannot identify merged (" + merged + ") and the fit re-polished");
  return true;
}

// The values a fit returns lie inside the bounds exactly: exp(ln p) may land one ulp outside
// (alpha2_I = 3.0000000000000004 against an upper bound of 3), and a card reader refuses that.
void clamp_to_bounds(Problem& problem) {
  std::vector<double>& p = problem.natural();
  for (int i = 0; i < problem.num_parameters(); ++i) {
    if (problem.user_fixed()[i]) continue;
    p[i] = std::clamp(p[i], problem.lower(i), problem.upper(i));
    // exp(x) of a log parameter can underflow to 0, which only a linear modulus may hold.
    if (problem.is_log(i) && !problem.specs()[i].linear && !(p[i] > 0.0))
      p[i] = std::max(problem.lower(i), std::numeric_limits<double>::min());
  }
}

// What the chosen backend ran: its last stage's outcome and what the assessment must know of it.
struct BackendRun {
  StageOutcome outcome;
  bool linear_only = false;     // nnls: only the linear parameters were fitted
  bool last_stage_set = false;  // staged: the covariance is over the last stage's set
  std::string used;             // the backends that ran, as the card records them
};

// The ceres and nlopt backends start from the linear solve, reviving moduli it set to 0.
void linear_start(Problem& problem, FitResult& result) {
  if (!has_free_linear(problem)) return;
  linear_stage(problem, result, false);
  revive_zero_moduli(problem, result);
}

BackendRun run_backend(Problem& problem, FitResult& result, const FitOptions& options) {
  BackendRun run;
  Backend backend = options.backend;
  if (backend == Backend::automatic && !has_free_nonlinear(problem)) backend = Backend::nnls;
  run.used = to_string(backend);
  switch (backend) {
    case Backend::nnls:
      run.outcome = linear_stage(problem, result, options.polish);
      run.linear_only = true;
      if (has_free_nonlinear(problem))
        result.messages.push_back("nnls: non-linear parameters held at their start values");
      break;
    case Backend::ceres:
      linear_start(problem, result);
      run.outcome = ceres_stage(problem, result);
      break;
    case Backend::nlopt:
      linear_start(problem, result);
      nlopt_stage(problem, result, options.multistart, options.max_iterations);
      run.outcome = ceres_stage(problem, result);
      run.used = "nlopt+ceres";
      break;
    case Backend::staged:
      run.outcome = run_schedule(problem, result);
      run.last_stage_set = true;
      break;
    case Backend::automatic:
      run.used = options.descent == LocalDescent::normal_equations ? "lm" : "ceres";
      if (has_free_linear(problem)) run.used = "nnls+" + run.used;
      linear_start(problem, result);
      if (options.global) {
        nlopt_stage(problem, result, options.multistart, options.max_iterations);
        run.used += "+nlopt";
      }
      if (!options.global && wants_global_check(problem)) {
        const std::vector<double> start = problem.natural();
        StageOutcome local = ceres_with_fallback(problem, result, run.used);
        run.outcome = keep_global_if_lower(problem, result, start, local, run.used);
      } else {
        run.outcome = ceres_with_fallback(problem, result, run.used);
      }
      break;
  }
  return run;
}

// Covariance over what was fitted: the positive linear parameters (nnls), the last stage's set
// (staged) or every movable parameter; unidentifiable terms merged and the fit assessed again.
void assess_with_merges(Problem& problem, FitResult& result, const BackendRun& run) {
  const std::vector<int> last_free = problem.free();
  auto assess_fit = [&] {
    sort_series_terms(problem, result);
    clamp_to_bounds(problem);
    std::vector<int> fitted = movable(problem, run.last_stage_set ? last_free : all_free(problem));
    if (run.linear_only)
      fitted.erase(std::remove_if(fitted.begin(), fitted.end(),
                                  [&](int i) { return !problem.specs()[i].linear; }),
                   fitted.end());
    problem.set_free(fitted);
    detail::assess(problem, result);
  };
  assess_fit();
  for (int round = 0; round < 6 && problem.options().uncertainty && merge_unidentifiable_terms(problem, result, run.linear_only);
       ++round)
    assess_fit();
  if (run.linear_only)
    for (int i : all_free(problem))
      if (!problem.specs()[i].linear) {
        result.parameters[i].fixed = true;
        result.parameters[i].reason = "held at its start (the nnls backend fits linear parameters)";
      }
  for (const auto& pr : result.parameters)
    if (!std::isfinite(pr.value))
      throw core::NumericalError("fit: parameter " + pr.name + " is not finite after the fit");
}

}  // namespace

namespace {

// A free parameter that ends on its bound is not determined by the data: the optimum lies beyond the
// range the fit admits, and the card carries the bound, not a measured value.
void bound_warnings(FitResult& result) {
  for (const ParameterResult& p : result.parameters)
    if (p.at_bound)
      result.quality.warnings.push_back(p.name + " = " + core::short_number(p.value) +
                                        (p.unit.empty() || p.unit == "-" ? "" : " " + p.unit) + " ended on its bound: the data do not determine it (the best fit "
                                        "lies beyond the admitted range), so the card holds the bound; read the card "
                                        "only within its data window");
}

}  // namespace

FitResult fit(const model::ModelPtr& model, const data::DynamicTestTable& table,
              const FitOptions& options, const std::vector<double>* start) {
  if (!model) throw core::UsageError("fit: no model");
  const core::Stopwatch clock;
  detail::check_single_temperature(*model, table);
  std::vector<double> natural_start =
      start ? *start : model->initial_parameters(summarize(table));
  Problem problem(model, table, options, std::move(natural_start));
  FitResult result;
  result.model = model;
  result.objective = describe_objective(options);
  for (const auto& n : problem.notes()) result.messages.push_back(n);
  admit_start(problem, result);
  if (!std::isfinite(problem.cost(problem.natural())))
    throw core::NumericalError("fit: model '" + model->kind() +
                               "' cannot be evaluated at the start: " +
                               problem.diagnose(problem.natural()));

  const BackendRun run = run_backend(problem, result, options);
  result.backend_used = run.used;
  readmit(problem, result, run.linear_only);
  assess_with_merges(problem, result, run);
  result.quality = detail::quality_verdict(problem, problem.natural());
  detail::degrees_of_freedom_warning(result.metrics, result.quality);
  bound_warnings(result);
  result.metrics.converged = run.outcome.converged;
  result.metrics.iterations = run.outcome.iterations;
  result.metrics.wall_time_s = clock.seconds();
  return result;
}

}  // namespace fitlib::fit
