// One load increment's Newton iterations and their step policy (newton.hpp).
#include "newton.hpp"

#include <cmath>

namespace fitlib::segment::detail {
namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

struct Newton::Attempt {
  double lambda;
  const Eigen::VectorXd& q_start;
  Eigen::VectorXd dq_p;  // the prescribed step (the predictor's coupling)
  bool predictor, fresh;
  bool stale_step = false;      // the last step was taken on a kept factorisation
  bool shifted_retake = false;  // the last step was a Levenberg–Marquardt retake
  bool restored = false;        // r_ and K_ hold q_'s, kept from before its step (no assembly needed)
  Eigen::VectorXd q_prev, dq, rhs;
  double res_prev = kInfinity, alpha = 1.0, energy_prev = 0.0, best = kInfinity, mu = 0.0;
  double retake_res = kInfinity, best_iterate_res = kInfinity;
  double res_before = kInfinity;  // the residual at the start of the step before the last
  int since_best = 0;  // assemblies without a new lowest residual
  NewtonOutcome o;
};

NewtonOutcome Newton::iterate(double lambda, const Eigen::VectorXd& q_start, bool extrapolated) {
  Attempt at{lambda, q_start, q_start - q_, !extrapolated, !extrapolated || !knobs_.reuse_tangent};
  at.rhs.resize(d_.equations);
  q_last_ = q_;
  if (extrapolated) q_ = q_start;
  best_q_.resize(0);
  kept_ = false;
  for (int it = 0; it < knobs_.max_iterations; ++it) {
    // (A restored start leaves the point states at the rejected iterate's: giving up there
    // re-evaluates them before q_ is accepted.)
    const bool states_elsewhere = at.restored;
    const bool skip_tangent = !at.restored && predicted_converged(at);
    at.o.bad_element =
        at.restored ? -1 : assemble(q_, lambda, at.predictor ? &at.dq_p : nullptr, at.fresh && !skip_tangent, &at.o);
    at.restored = false;
    double res = at.o.bad_element >= 0 ? kInfinity : free_norm(r_, d_, true);
    at.o.residual_only += skip_tangent;
    if (skip_tangent && !(res <= knobs_.tolerance * (free_norm(r_, d_, false) + 1.0))) {  // mispredicted: with K
      at.o.bad_element = assemble(q_, lambda, nullptr, true, &at.o);
      res = at.o.bad_element >= 0 ? kInfinity : free_norm(r_, d_, true);
    }
    at.o.residual = res;
    const Rise rise = on_rise(at, res);
    if (rise == Rise::retry) continue;
    if (rise == Rise::stop || !std::isfinite(res)) return at.o;
    const double scale = free_norm(r_, d_, false) + 1.0;
    if (!at.predictor && res < at.best_iterate_res) at.best_iterate_res = res, best_q_ = q_;  // (the predictor's is the old q)
    if (res < at.best) at.best = res, at.since_best = 0;
    else if (++at.since_best > knobs_.stall_iterations) return give_up(at, res, scale, states_elsewhere);
    if (!at.predictor && res <= knobs_.tolerance * scale) {
      at.o.converged = true;
      return at.o;
    }
    adapt_shift(at, res);
    if (!step(at, res)) return give_up(at, res, scale, states_elsewhere);
  }
  // Out of assemblies: the last iterate, evaluated (the loop may end on a step not yet assembled,
  // and the committed states must be its own), accepted at the loose tolerance as a stalled one is.
  at.o.bad_element = assemble(q_, lambda, nullptr, false, &at.o);
  at.o.residual = at.o.bad_element >= 0 ? kInfinity : free_norm(r_, d_, true);
  at.o.converged = at.o.residual <= knobs_.stall_tolerance * (free_norm(r_, d_, false) + 1.0);
  return at.o;
}

// Whether the next assembly will show convergence, so needs no tangent: after two full, unshifted
// Newton steps on fresh tangents that contracted, the quadratic rate r_next ≈ r² · (r / r_before²)
// predicts a residual below kConvergedMargin of the tolerance. A wrong prediction costs the
// assembly again with the tangent; the residual, and so every decision, is the same either way.
bool Newton::predicted_converged(const Attempt& at) const {
  if (at.predictor || !at.fresh || at.stale_step || at.shifted_retake || at.mu > 0.0 || at.alpha != 1.0) return false;
  const double r = at.res_prev, before = at.res_before;
  if (!(r < before) || !std::isfinite(before) || !(r > 0.0)) return false;
  const double predicted = r * r * r / (before * before);
  return predicted <= kConvergedMargin * knobs_.tolerance * (free_norm(r_, d_, false) + 1.0);
}

Newton::Rise Newton::on_rise(Attempt& at, double res) {
  const bool worse = !(res < at.res_prev) && !(std::isfinite(res) && energy(at.dq) < kEnergyDrop * at.energy_prev);
  if (!worse || !std::isfinite(at.res_prev)) return Rise::none;
  if (at.stale_step) {  // 1. a kept factorisation's step: retaken on a fresh tangent
    q_ = at.q_prev, at.fresh = true, at.stale_step = false, at.res_prev = kInfinity;
    return Rise::retry;
  }
  if (at.alpha == 1.0 && knobs_.levenberg > 0.0 && at.mu < kLargestShift * knobs_.levenberg) {  // 2.
    if (++at.since_best > knobs_.stall_iterations) return Rise::stop;
    at.mu = at.mu > 0.0 ? 10.0 * at.mu : knobs_.levenberg;  // retake the step from its start on K + μ·diag|K|
    q_ = at.q_prev, at.fresh = true, at.res_prev = kInfinity, at.shifted_retake = true;
    at.restored = restore_kept();  // the retake's start was an iterate: its K and r need no assembly
    return Rise::retry;
  }
  if (at.alpha > kSmallestStep) {  // 3. the line search (halvings count towards the stall)
    if (++at.since_best > knobs_.stall_iterations) return Rise::stop;
    at.alpha *= 0.5;
    move(at.q_prev, at.dq, at.alpha);
    return Rise::retry;
  }
  if (at.res_prev <= knobs_.stall_tolerance * (free_norm(r_, d_, false) + 1.0)) {
    q_ = at.q_prev;  // 4. no step lowers the residual, which is below the loose tolerance: accept its start
    at.o.bad_element = assemble(q_, at.lambda, nullptr, false, &at.o);  // the trial states at q_prev
    at.o.residual = at.res_prev;
    at.o.converged = at.o.bad_element < 0;
    return Rise::stop;
  }
  return Rise::none;
}

NewtonOutcome Newton::give_up(Attempt& at, double res, double scale, bool states_elsewhere) {
  NewtonOutcome& o = at.o;
  o.converged = !at.predictor && res <= knobs_.stall_tolerance * scale;
  if (o.converged && states_elsewhere) o.bad_element = assemble(q_, at.lambda, nullptr, false, &o);
  o.converged = o.converged && o.bad_element < 0;
  return o;
}

void Newton::adapt_shift(Attempt& at, double res) {
  // After a shifted step the shift follows the residual (switched evolution relaxation).
  if (!at.shifted_retake && at.mu > 0.0)
    at.mu = at.mu * res / at.res_prev < kNegligibleShift ? 0.0 : at.mu * res / at.res_prev;
  if (at.shifted_retake) at.retake_res = res;
  else if (res < at.retake_res) at.mu = 0.0;  // below the overshoot's start: Newton's basin, no shift
  at.shifted_retake = false;
}

bool Newton::step(Attempt& at, double res) {
  keep(at.fresh && !at.predictor && knobs_.levenberg > 0.0);  // before the shift: a retake from here restores it
  if (at.fresh && at.mu > 0.0) shift_diagonal(at.mu);
  for (int i = 0; i < r_.size(); ++i)
    if (d_.eq[i] >= 0) at.rhs(d_.eq[i]) = -r_(i);
  if (at.predictor) at.rhs -= coupling_;
  // (Modified Newton keeps a factorisation of K for its later steps: no GMRES then.)
  const int krylov = knobs_.reuse_tangent ? 0 : knobs_.krylov_iterations;
  // Near convergence the tangent has moved little since the last factorisation (not across an
  // increment's start nor a shifted step: there it moves most).
  const bool kept = !at.predictor && at.mu == 0.0 && res <= knobs_.keep_preconditioner_below * (free_norm(r_, d_, false) + 1.0);
  bool factorized = false;  // K, or its symmetric part for GMRES (counted once per tangent)
  if (!(at.fresh && linear_.krylov_solve(K_.K, at.rhs, krylov, knobs_.krylov_tolerance, kept, at.dq, factorized))) {
    if (at.fresh && !linear_.factorize(K_.K)) return false;
    factorized = factorized || at.fresh;
    at.dq = linear_.solve(at.rhs);
  }
  at.o.factorizations += factorized;
  if (!at.dq.allFinite()) return false;
  const bool slow = at.stale_step && !(res <= kReuseContraction * at.res_prev);
  at.stale_step = !at.fresh;
  at.q_prev = at.predictor ? at.q_start : q_;  // the predictor step is taken whole
  at.res_before = at.res_prev;
  at.res_prev = at.predictor ? kInfinity : res;
  at.energy_prev = std::abs(at.rhs.dot(at.dq));
  at.alpha = 1.0;
  move(at.q_prev, at.dq, 1.0);
  if (at.predictor && rotation_.size() == q_.size()) q_ += rotation_;
  at.predictor = false;
  at.fresh = !knobs_.reuse_tangent || slow;
  at.o.iterations++;
  return true;
}

// The node carrying the largest free residual component of the last assembly (-1: none).
int Newton::worst_node() const {
  int worst = -1;
  double largest = -1.0;
  for (int i = 0; i < r_.size(); ++i)
    if (d_.eq[i] >= 0 && std::abs(r_(i)) > largest) largest = std::abs(r_(i)), worst = i / 2;
  return worst;
}

// From the converged q to load level λ; q_start holds the prescribed components at λ and the
// free ones' start (`extrapolated`: the last increment's motion extrapolated, iterated on the
// kept factorisation with `reuse_tangent`, else on a fresh tangent; otherwise the last converged
// values, and the first iteration is the linear predictor).
NewtonOutcome Newton::solve(double lambda, const Eigen::VectorXd& q_start, bool extrapolated) {
  NewtonOutcome o = iterate(lambda, q_start, extrapolated);
  if (o.converged || !extrapolated) return o;
  const NewtonOutcome extrapolation = o;
  Eigen::VectorXd linear_start = q_start;  // the extrapolation led astray: the linear predictor
  for (int i = 0; i < q_start.size(); ++i)
    if (d_.eq[i] >= 0) linear_start(i) = q_last_(i);
  q_ = q_last_;
  o = iterate(lambda, linear_start, false);
  o.iterations += extrapolation.iterations, o.factorizations += extrapolation.factorizations;
  o.assemblies += extrapolation.assemblies, o.residual_only += extrapolation.residual_only;
  return o;
}

// The element loop at q: r_, and K_ when `tangent` (the predictor's coupling with `dq_p`).
int Newton::assemble(const Eigen::VectorXd& q, double lambda, const Eigen::VectorXd* dq_p, bool tangent, NewtonOutcome* o) {
  ++o->assemblies;
  a_.set_follows_step(dq_p == nullptr);  // the predictor's assembly is at the last converged q
  const int bad = a_.run(q, lambda, dq_p, r_, tangent ? &K_ : nullptr, dq_p ? &coupling_ : nullptr);
  a_.set_follows_step(false);
  return bad;
}

// The unshifted tangent and the residual of the iterate a step is taken from (`valid`: they are
// its own, not the predictor's linearisation about the last increment's state).
void Newton::keep(bool valid) {
  kept_ = valid;
  if (!valid) return;
  kept_K_.assign(K_.K.valuePtr(), K_.K.valuePtr() + K_.K.nonZeros());
  kept_r_ = r_;
}

bool Newton::restore_kept() {
  if (!kept_) return false;
  std::copy(kept_K_.begin(), kept_K_.end(), K_.K.valuePtr());
  r_ = kept_r_;
  return true;
}

// K_ii += μ |K_ii| (Marquardt's scaling: the shift is unit-free and leaves stiff dofs stiff).
void Newton::shift_diagonal(double mu) {
  double* K = K_.K.valuePtr();
  for (int e = 0; e < d_.equations; ++e) K[diagonal_[e]] += mu * std::abs(K[diagonal_[e]]);
}

double Newton::energy(const Eigen::VectorXd& dq) const {
  double e = 0.0;
  for (int i = 0; i < r_.size() && dq.size(); ++i)
    if (d_.eq[i] >= 0) e += r_(i) * dq(d_.eq[i]);
  return std::abs(e);
}

void Newton::move(const Eigen::VectorXd& from, const Eigen::VectorXd& dq, double alpha) {
  q_ = from;
  for (int i = 0; i < q_.size(); ++i)
    if (d_.eq[i] >= 0) q_(i) += alpha * dq(d_.eq[i]);
}

}  // namespace fitlib::segment::detail
