#include "fitlib/fatigue/life_fit.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>

#include "fitlib/core/error.hpp"

namespace fitlib::fatigue {

namespace {

constexpr double kLn2 = 0.69314718055994531, kLn10 = 2.30258509299404568;

// log10 N = −ln S/ln 10 − b ΔT log10 2, S = max over points of Σ exp(n (ln σ_i − ln σ0)),
// summed by log-sum-exp so that large n do not overflow.
template <typename T>
T log10_life(const ObservedLife& c, const T& ln_sigma0, const T& n, const T& b, double dT) {
  using std::exp;
  using std::log;
  T best_ln_sum = T(-1e300);
  for (const std::vector<double>& peaks : c.point_peaks_MPa) {
    if (peaks.empty()) continue;
    T top = n * (std::log(peaks[0]) - ln_sigma0);
    for (double p : peaks) top = std::max(top, T(n * (std::log(p) - ln_sigma0)));
    T sum = T(0.0);
    for (double p : peaks) sum += exp(n * (std::log(p) - ln_sigma0) - top);
    const T ln_sum = top + log(sum);
    if (ln_sum > best_ln_sum) best_ln_sum = ln_sum;
  }
  return -best_ln_sum / kLn10 - b * dT * (kLn2 / kLn10);
}

struct LogLifeResidual {
  const ObservedLife* c;
  double dT;
  template <typename T>
  bool operator()(const T* ln_sigma0, const T* n, const T* b, T* r) const {
    r[0] = log10_life(*c, ln_sigma0[0], n[0], b[0], dT) - T(std::log10(c->observed_cycles));
    if (c->runout && r[0] > T(0.0)) r[0] = T(0.0);  // a runout bounds the life from below only
    return true;
  }
};

// The failures of `mode` first, then its runouts (InputError when none failed in it).
std::vector<const ObservedLife*> cases_of(const std::vector<ObservedLife>& all, Mode mode) {
  std::vector<const ObservedLife*> cases;
  for (const bool runout : {false, true})
    for (const ObservedLife& c : all)
      if (c.mode == mode && c.runout == runout) cases.push_back(&c);
  if (cases.empty() || cases.front()->runout)
    throw core::InputError(std::string("no observed lives with failure mode ") + to_string(mode),
                           "", 0, 0, "failure_mode");
  return cases;
}

// The free coordinates (ln σ0, n, b) and the problem on them; Ceres solves in place.
struct LifeProblem {
  double ln_sigma0 = 0.0, n = 0.0, b = 0.0;
  bool fix_n = false, fix_b = false;
  ceres::Problem problem;
};

void solve_life_problem(const std::vector<const ObservedLife*>& cases, const LifeFitOptions& o,
                        Mode mode, LifeProblem& lp) {
  lp.ln_sigma0 = std::log(o.start.sigma0_MPa), lp.n = o.start.n, lp.b = o.start.b_per_C;
  for (const ObservedLife* c : cases)
    lp.problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<LogLifeResidual, 1, 1, 1, 1>(
            new LogLifeResidual{c, c->temperature_C - o.reference_temperature_C}),
        nullptr, &lp.ln_sigma0, &lp.n, &lp.b);
  lp.problem.SetParameterLowerBound(&lp.n, 0, kExponentMin);
  lp.problem.SetParameterUpperBound(&lp.n, 0, kExponentMax);
  if (lp.fix_n) lp.problem.SetParameterBlockConstant(&lp.n);
  if (lp.fix_b) lp.problem.SetParameterBlockConstant(&lp.b);
  ceres::Solver::Options options;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &lp.problem, &summary);
  if (!summary.IsSolutionUsable() || !std::isfinite(summary.final_cost))
    throw core::NumericalError(std::string("fatigue: life-constant fit of ") + to_string(mode) +
                               " failed: " + summary.message);
}

// Jacobian of the residuals in the free coordinates (ln σ0, n[, b]) at the solution.
Eigen::MatrixXd jacobian_at_solution(LifeProblem& lp, std::vector<double>& residuals) {
  std::vector<double*> blocks = {&lp.ln_sigma0};
  if (!lp.fix_n) blocks.push_back(&lp.n);
  if (!lp.fix_b) blocks.push_back(&lp.b);
  ceres::Problem::EvaluateOptions eo;
  eo.parameter_blocks = blocks;
  double cost = 0.0;
  ceres::CRSMatrix crs;
  lp.problem.Evaluate(eo, &cost, &residuals, nullptr, &crs);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r)
    for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) J(r, crs.cols[k]) = crs.values[k];
  return J;
}

void add_note(std::string& note, const std::string& text) { note += (note.empty() ? "" : "; ") + text; }

// 95 % intervals from the covariance s²(JᵀJ)⁻¹ (Student t with m − p degrees of freedom); σ0's
// from ln σ0's, exponentiated (stays positive), with a delta-method standard error. A note
// instead when there are too few cases or the constants are not identifiable. J's columns are
// the free constants in est's order.
// The covariance goes to `law` (the card's, ln σ0, n, b with zeros for held constants) and the
// residual standard deviation s = √(ss/(m − p)) to its scatter (docs/fatigue.md §9).
void add_intervals(const Eigen::MatrixXd& J, double ss, double ln_sigma0,
                   std::vector<ConstantEstimate>& est, std::string& note, LifeLaw& law) {
  const int m = static_cast<int>(J.rows()), p = static_cast<int>(J.cols());
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
  if (m <= p) {
    add_note(note, "no intervals: " + std::to_string(m) + " case(s) for " + std::to_string(p) + " free constant(s)");
    return;
  }
  if (!lu.isInvertible()) {
    add_note(note, "no intervals: the constants are not identifiable from these cases");
    return;
  }
  const Eigen::MatrixXd cov = lu.inverse() * (ss / (m - p));
  const double t = boost::math::quantile(boost::math::students_t(m - p), 0.975);
  std::vector<ConstantEstimate*> free;
  std::vector<std::size_t> slot;  // each free constant's place in (ln σ0, n, b)
  for (std::size_t k = 0; k < est.size(); ++k)
    if (!est[k].fixed) free.push_back(&est[k]), slot.push_back(k);
  LawCovariance full{};
  for (int i = 0; i < p; ++i)
    for (int k = 0; k < p; ++k) full[slot[i]][slot[k]] = 0.5 * (cov(i, k) + cov(k, i));  // symmetric to the bit
  law.covariance = full;
  law.scatter = LifeScatter{"lognormal", std::sqrt(ss / (m - p)), m - p};
  for (int k = 0; k < p; ++k) {
    ConstantEstimate& e = *free[k];
    const double se = std::sqrt(std::max(cov(k, k), 0.0));
    e.has_interval = true;
    if (k == 0) {
      e.std_error = e.value * se;
      e.ci95_low = std::exp(ln_sigma0 - t * se);
      e.ci95_high = std::exp(ln_sigma0 + t * se);
    } else {
      e.std_error = se;
      e.ci95_low = e.value - t * se;
      e.ci95_high = e.value + t * se;
    }
  }
}

}  // namespace

double predicted_log10_life(const ObservedLife& c, const LifeLaw& law, double reference_C) {
  return log10_life(c, std::log(law.sigma0_MPa), law.n, law.b_per_C, c.temperature_C - reference_C);
}

std::vector<std::string> violated_runouts(const std::vector<ObservedLife>& cases, Mode mode, const LifeLaw& law,
                                          double reference_C, double slack_log10) {
  std::vector<std::string> out;
  for (const ObservedLife& c : cases) {
    if (!c.runout || c.mode != mode) continue;
    const double predicted = predicted_log10_life(c, law, reference_C);
    if (predicted < std::log10(c.observed_cycles) - slack_log10)
      out.push_back(c.name + " (predicted " + core::short_number(std::pow(10.0, predicted)) + " cycles, stopped at " +
                    core::short_number(c.observed_cycles) + ")");
  }
  return out;
}

LifeFitResult fit_life_law(const std::vector<ObservedLife>& all, Mode mode, const LifeFitOptions& o) {
  const std::vector<const ObservedLife*> cases = cases_of(all, mode);
  LifeFitResult result;
  result.mode = mode;
  for (const ObservedLife* c : cases) ++(c->runout ? result.runouts : result.cases);
  bool one_temperature = true;
  for (const ObservedLife* c : cases)
    one_temperature = one_temperature && (c->runout || c->temperature_C == cases[0]->temperature_C);
  // No more free constants than failures: b needs two temperatures and a third case, n a second case.
  const std::size_t m = static_cast<std::size_t>(result.cases);
  LifeProblem lp;
  lp.fix_n = o.fix_n || m < 2;
  lp.fix_b = o.fix_b || one_temperature || m < 3;
  if (lp.fix_n && !o.fix_n) add_note(result.note, "n held at its start value: one case fixes sigma0 alone");
  if (lp.fix_b && !o.fix_b)
    add_note(result.note, one_temperature ? "b held at its start value: all cases at one temperature"
                                          : "b held at its start value: two cases cannot fix three constants");
  solve_life_problem(cases, o, mode, lp);
  result.law = {std::exp(lp.ln_sigma0), lp.n, lp.b, cases[0]->stress_fidelity};  // one level per mode

  std::vector<double> residuals;
  const Eigen::MatrixXd all_rows = jacobian_at_solution(lp, residuals);
  // The failures and the runouts the law violates (a satisfied runout's row is zero: no information).
  std::vector<Eigen::Index> active;
  double ss = 0.0;
  for (std::size_t k = 0; k < cases.size(); ++k)
    if (!cases[k]->runout || residuals[k] < 0.0) active.push_back(static_cast<Eigen::Index>(k)), ss += residuals[k] * residuals[k];
  const Eigen::MatrixXd J = all_rows(active, Eigen::all);
  result.rms_log10_error = std::sqrt(ss / static_cast<double>(J.rows()));
  result.constants = {{"sigma0_MPa", "MPa", result.law.sigma0_MPa},
                      {"n", "1", lp.n, lp.fix_n},
                      {"b_per_C", "1/°C", lp.b, lp.fix_b}};
  add_intervals(J, ss, lp.ln_sigma0, result.constants, result.note, result.law);
  result.violated_runouts = violated_runouts(all, mode, result.law, o.reference_temperature_C, kScatterWarning_log10);
  return result;
}

}  // namespace fitlib::fatigue
