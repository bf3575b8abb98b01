#pragma once
// One load increment's Newton iterations (solver.cpp; docs/segment.md §Solver), with a named step
// policy. A step is taken on the consistent tangent (or, with `reuse_tangent`, on a kept
// factorisation while the residual contracts by kReuseContraction per iteration: modified Newton).
// A step that makes no progress — lowers neither the free residual norm nor the energy measure
// |Δq·r| below kEnergyDrop of its start (a near-incompressible body's residual may rise on the way),
// or inverts an element — is met, in this order, by:
//   1. a retake on a fresh tangent, when it was taken on a kept factorisation;
//   2. a Levenberg–Marquardt retake from its start on K + μ·diag|K| (`levenberg`; μ ×10 per failed
//      retake up to kLargestShift × levenberg), the shift then scaled by each step's residual ratio
//      and dropped once the residual is below the retaken step's start;
//   3. a line search halving the step down to kSmallestStep;
//   4. acceptance of the step's start when its residual is below the loose (stall) tolerance.
// Without a new lowest residual for `stall_iterations` assemblies the increment gives up (accepted
// at the loose tolerance, else a failure the stepping cuts).
#include <limits>

#include <Eigen/Core>

#include "assembler.hpp"
#include "dofs.hpp"
#include "linear_solver.hpp"
#include "fitlib/segment/solver.hpp"

namespace fitlib::segment::detail {

struct NewtonOutcome {
  bool converged = false;
  int iterations = 0, factorizations = 0, assemblies = 0, residual_only = 0, bad_element = -1;
  double residual = std::numeric_limits<double>::infinity();
};

class Newton {
 public:
  // A step makes progress when its energy measure falls below this share of its start's.
  static constexpr double kEnergyDrop = 0.8;
  // The Levenberg–Marquardt retakes stop at this multiple of the first shift.
  static constexpr double kLargestShift = 1e4;
  // The line search's shortest step (five halvings).
  static constexpr double kSmallestStep = 1.0 / 32.0;
  // With `reuse_tangent`, a kept factorisation serves while the residual contracts by this per step.
  static constexpr double kReuseContraction = 0.25;
  // A shift scaled below this is dropped (the iteration is back in Newton's basin).
  static constexpr double kNegligibleShift = 1e-9;
  // An assembly is made without the tangent when its residual is predicted below this share of the
  // tolerance (predicted_converged).
  static constexpr double kConvergedMargin = 1e-2;

  Newton(const Assembler& a, Pattern& K, LinearSolver& linear, const Dofs& d, const NewtonOptions& knobs,
         Eigen::VectorXd& q)
      : a_(a), K_(K), linear_(linear), d_(d), knobs_(knobs), q_(q), diagonal_(diagonal_slots(K.K)) {}

  // The node carrying the largest free residual component of the last assembly (-1: none).
  int worst_node() const;
  // Added to the predictor's step (local components; empty: none): the second-order part of the
  // nodes' finite rotation with the loading.
  void set_rotation(Eigen::VectorXd rotation) { rotation_ = std::move(rotation); }
  // Per equation, the slot of K_ii in K's values.
  const std::vector<int>& diagonal() const { return diagonal_; }
  // The iterate with the lowest residual of the last solve (empty before one).
  const Eigen::VectorXd& best_iterate() const { return best_q_; }
  // The last assembly's residual (local components, all dofs): at the converged q after a solve
  // that converged.
  const Eigen::VectorXd& residual() const { return r_; }

  // From the converged q to load level λ; q_start holds the prescribed components at λ and the
  // free ones' start (`extrapolated`: the last increment's motion extrapolated, iterated on the
  // kept factorisation with `reuse_tangent`, else on a fresh tangent; otherwise the last converged
  // values, and the first iteration is the linear predictor). A failed extrapolated start is
  // retaken from the linear predictor.
  NewtonOutcome solve(double lambda, const Eigen::VectorXd& q_start, bool extrapolated);

 private:
  struct Attempt;  // one start's iteration state (newton.cpp)
  enum class Rise { none, retry, stop };

  NewtonOutcome iterate(double lambda, const Eigen::VectorXd& q_start, bool extrapolated);
  // Whether the next assembly is predicted to show convergence (no tangent needed; newton.cpp).
  bool predicted_converged(const Attempt& at) const;
  // The step policy's answer to an iterate whose residual `res` made no progress (steps 1–4 above).
  Rise on_rise(Attempt& at, double res);
  // Gives up at this iterate (stalled, or no step to take): accepted at the loose tolerance.
  NewtonOutcome give_up(Attempt& at, double res, double scale, bool states_elsewhere);
  // The shift after a step: scaled by the residual ratio, dropped in Newton's basin.
  void adapt_shift(Attempt& at, double res);
  // Solves for the next step and takes it; false when the linear solve failed.
  bool step(Attempt& at, double res);

  // The element loop at q: r_, and K_ when `tangent` (the predictor's coupling with `dq_p`).
  int assemble(const Eigen::VectorXd& q, double lambda, const Eigen::VectorXd* dq_p, bool tangent, NewtonOutcome* o);
  // The unshifted tangent and the residual of the iterate a step is taken from (`valid`: they are
  // its own, not the predictor's linearisation about the last increment's state).
  void keep(bool valid);
  bool restore_kept();
  // K_ii += μ |K_ii| (Marquardt's scaling: the shift is unit-free and leaves stiff dofs stiff).
  void shift_diagonal(double mu);
  double energy(const Eigen::VectorXd& dq) const;
  void move(const Eigen::VectorXd& from, const Eigen::VectorXd& dq, double alpha);

  const Assembler& a_;
  Pattern& K_;
  LinearSolver& linear_;
  const Dofs& d_;
  const NewtonOptions& knobs_;
  Eigen::VectorXd& q_;
  Eigen::VectorXd q_last_, r_, coupling_, best_q_, rotation_;
  std::vector<int> diagonal_;  // per equation: the slot of K_ii in K's values
  bool kept_ = false;          // kept_K_ and kept_r_ are the last step's start (keep)
  std::vector<double> kept_K_;
  Eigen::VectorXd kept_r_;
};

}  // namespace fitlib::segment::detail
