// Quasi-static finite-strain solve of a plane-strain mesh (fitlib/segment/solver.hpp): load
// stepping over λ with step cuts that grow back; each increment's Newton iterations (newton.hpp) on
// the element loop (assembler.hpp) over the unknowns and pattern of dofs.hpp; observers called
// after each converged increment.
#include "fitlib/segment/solver.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <thread>

#include "assembler.hpp"
#include "critical_mode.hpp"
#include "diagnosis.hpp"
#include "dofs.hpp"
#include "inertia.hpp"
#include "linear_solver.hpp"
#include "newton.hpp"
#include "worker_pool.hpp"
#include "fitlib/core/error.hpp"

namespace fitlib::segment {

int gauss_order(const Mesh& mesh, Integration integration) {
  return (mesh.nodes_per_element == 8 && integration != Integration::reduced) ? 3 : 2;
}

namespace {
using detail::Assembler;
using detail::Dofs;
using detail::LinearSolver;
using detail::Newton;
using detail::NewtonOutcome;
using detail::Pattern;
using detail::StateBlock;
using detail::build_pattern;
using detail::free_norm;
using detail::initial_states;
using detail::number_dofs;
using detail::ordered_pattern;

// An increment that failed from the rotated predictor is retaken without its rotation terms only
// when they moved the start by more than this (Euclidean norm over the nodes).
constexpr double kRetakeRotation_mm = 1e-4;

// Increment targets: the schedule's breakpoints, or `steps` equal increments of λ.
std::vector<double> breakpoints(const SteppingOptions& stepping) {
  const std::vector<double>& schedule = stepping.schedule;
  if (!schedule.empty()) {
    for (std::size_t k = 0; k < schedule.size(); ++k)
      if (!(schedule[k] > (k ? schedule[k - 1] : 0.0)) || schedule[k] > 1.0)
        throw core::UsageError("segment: the load schedule must increase within (0, 1]");
    std::vector<double> b = schedule;
    if (b.back() < 1.0) b.push_back(1.0);
    return b;
  }
  std::vector<double> b;
  const int n = std::max(1, stepping.steps);
  for (int k = 1; k <= n; ++k) b.push_back(static_cast<double>(k) / n);
  return b;
}

// The dynamics' inertia load (PhysicsOptions::inertia; segment/inertia.hpp), when the problem has a
// mass and a time; null otherwise.
std::unique_ptr<detail::BackwardEulerInertia> make_inertia(const StaticProblem& p, const SolverKnobs& knobs) {
  if (!(knobs.physics.inertia && p.density_t_mm3 > 0.0 && p.time_s)) return nullptr;
  detail::BackwardEulerInertia::FrameMotion frame;
  if (p.motion->has_frame())
    frame = [motion = p.motion](double lambda, std::vector<Eigen::Vector2d>& u) { motion->frame_motion(lambda, u); };
  return std::make_unique<detail::BackwardEulerInertia>(detail::lumped_masses(*p.mesh, p.density_t_mm3), frame);
}

// The problem's loads in their order, then the solver's own (the inertia).
std::vector<Load*> loads_of(const StaticProblem& p, Load* inertia) {
  std::vector<Load*> loads;
  for (const LoadPtr& load : p.loads) loads.push_back(load.get());
  if (inertia) loads.push_back(inertia);
  return loads;
}

// LDLᵀ when every law's tangent, the element's and every load's are symmetric.
bool symmetric_problem(const StaticProblem& p, const SolverKnobs& knobs) {
  return p.laws[0]->symmetric_tangent() && p.laws[1]->symmetric_tangent() && symmetric_tangent(knobs.physics.integration) &&
         std::all_of(p.loads.begin(), p.loads.end(), [](const LoadPtr& load) { return load->symmetric(); });
}

// One run of solve_static: Newton increments from λ = 0 to 1 with step cuts that grow back.
class StaticRun {
 public:
  StaticRun(const StaticProblem& p, const SolverKnobs& knobs)
      : p_(p), knobs_(knobs), m_(*p.mesh), d_(number_dofs(p)), angles_(p.constraints.size()),
        pool_(solver_threads(knobs)), inertia_(make_inertia(p, knobs)),
        assembler_(p, d_, gauss_order(m_, knobs.physics.integration), knobs.physics.integration == Integration::fbar, pool_,
                   loads_of(p, inertia_.get())),
        states_(initial_states(p, assembler_.points_per_element())), scratch_(states_.committed.size()),
        linear_(symmetric_problem(p, knobs), &pool_, knobs.newton.split_factorisation),
        pattern_(linear_.symmetric() || knobs.newton.krylov_iterations > 0 ? ordered_pattern(m_, d_) : build_pattern(m_, d_)), nn_(m_.node_count()), q_(Eigen::VectorXd::Zero(2 * nn_)),
        newton_(assembler_, pattern_, linear_, d_, knobs.newton, q_), values_(p.constraints.size()) {
    assembler_.set_offsets(&states_.offset);
    assembler_.set_diagonal(&newton_.diagonal());
    assembler_.set_linearised_pressure(knobs.newton.linearised_pressure && !knobs.newton.reuse_tangent);
    out_.equations = d_.equations;
    out_.threads = pool_.threads();
  }

  StaticSolution run() {
    const std::vector<double> targets = breakpoints(knobs_.stepping);
    std::size_t next = 0;
    while (next < targets.size()) {
      const double target = std::min(targets[next], lambda_ + max_step_);
      if (increment(target)) {
        if (target >= targets[next]) ++next;
      } else if (++cuts_in_row_ > knobs_.stepping.max_cuts) {
        if (!switch_branch(target))
          fail(out_.increments + 1, target, last_.bad_element, last_.residual, last_.iterations);
        if (target >= targets[next]) ++next;
        max_step_ = uncut_step_;  // on the new branch the increments go on at the step that failed
      } else {
        if (cuts_in_row_ == 1) uncut_step_ = target - lambda_;
        max_step_ = 0.5 * (target - lambda_);
        out_.cuts++;
      }
    }
    snapshot(out_);
    out_.pattern_analyses = linear_.analyses();
    out_.krylov_iterations = linear_.krylov_iterations();
    out_.krylov_fallbacks = linear_.krylov_fallbacks();
    out_.symmetric_solver = linear_.symmetric();
    out_.split_factorisation = linear_.split();
    out_.state = states_.committed;
    out_.state_offset = states_.offset;
    return out_;
  }

 private:
  double time_at(double lambda) const { return p_.time_s ? p_.time_s(lambda) : 0.0; }

  // q with the prescribed components at λ.
  Eigen::VectorXd prescribed_at(double lambda) {
    Eigen::VectorXd qp = q_;
    p_.motion->values(lambda, values_);
    for (std::size_t c = 0; c < p_.constraints.size(); ++c)
      for (int k = 0; k < 2; ++k)
        if (p_.constraints[c].fixed[k]) qp(2 * p_.constraints[c].node + k) = values_[c][k];
    return qp;
  }

  [[noreturn]] void fail(int increment, double lambda, int element, double residual, int iterations) {
    std::ostringstream msg;
    msg << "segment: Newton failed in load increment " << increment << " (lambda " << lambda;
    if (p_.time_s) msg << ", t " << time_at(lambda) << " s";
    msg << ")";
    if (element >= 0) msg << ", element " << element << " inverted or with a non-finite stress";
    msg << ", free residual " << residual << " N/mm after " << iterations << " iterations and "
        << knobs_.stepping.max_cuts << " step cuts";
    // Where: on the complete level a residual stuck near one node with no inverted element is a fold
    // of the load path there (docs/segment.md "Cost", "Diagnosis at the failing state");
    // `diagnose_failure` says which.
    if (const int n = newton_.worst_node(); n >= 0)
      msg << "; largest residual at node " << n << " (reference x " << m_.X[n].x() << ", y " << m_.X[n].y()
          << " mm)";
    msg << branch_note_;
    if (knobs_.diagnose_failure) msg << diagnose(lambda);
    throw core::NumericalError(msg.str());
  }

  // The failure diagnosis at the increment's start (the last converged q with the prescribed motion
  // at λ) and at its best iterate, both on the step from the committed states.
  std::string diagnose(double lambda) {
    assembler_.set_step(states_.committed.data(), scratch_.data(), time_at(lambda) - time_at(lambda_));
    detail::DiagnosisProblem p;
    p.mesh = &m_, p.eq = &d_.eq, p.basis = &d_.R;
    p.residual = [&](const Eigen::VectorXd& q) {
      Eigen::VectorXd r;
      return assembler_.run(q, lambda, nullptr, r, nullptr, nullptr) >= 0 ? Eigen::VectorXd() : r;
    };
    p.tangent = [&](const Eigen::VectorXd& q) {
      Eigen::VectorXd r;
      assembler_.run(q, lambda, nullptr, r, &pattern_, nullptr);
      return pattern_.K;
    };
    p.element = [&](const Eigen::VectorXd& q, int e, detail::ElementVector& f, detail::ElementMatrix* K,
                    std::vector<detail::ElementState>* states) { return assembler_.element_at(q, e, f, K, states); };
    p.point = [&](int e, int g, const Eigen::Matrix2d& F, bool tangent) {
      const PlaneStrainLaw& law = assembler_.law_of(e);
      const detail::ElementStep step = assembler_.step_of(e);
      const std::size_t at = static_cast<std::size_t>(g) * law.state_size();
      return law.respond(F, {step.state_n + at, step.state_next + at, step.dt_s, step.temperature_C, tangent});
    };
    std::string text = detail::diagnose(p, prescribed_at(lambda), "increment start");
    if (newton_.best_iterate().size() == q_.size()) text += detail::diagnose(p, newton_.best_iterate(), "best iterate");
    return text;
  }

  // SteppingOptions::branch_switch: the failed increment to `target` retaken from its start moved by
  // ± the critical mode of the tangent there, when that mode's eigenvalue is ≤ 0 (a bifurcation
  // passed: the fundamental path is unstable and a neighbouring branch may carry the load). True
  // when a retake converged (committed as any increment); the finding goes into the exit-4 message.
  bool switch_branch(double target) {
    if (!(knobs_.stepping.branch_switch > 0.0)) return false;
    const detail::CriticalMode c = mode_at_start(target);
    std::ostringstream note;
    note << "; branch switch (" << out_.branch_switches << " increments carried before this one, step "
         << target - lambda_ << "): eigenvalue of K's symmetric part nearest zero at the increment's start "
         << c.eigenvalue << " N/mm², " << c.negative << " negative";
    if (c.mode.size() == 0 || c.eigenvalue > 0.0) {
      branch_note_ = note.str() + (c.mode.size() ? " (not tried: that mode is stable)" : " (not found)");
      return false;
    }
    double peak = 0.0;  // the mode's largest nodal displacement
    for (int a = 0; a < nn_; ++a) {
      Eigen::Vector2d v = Eigen::Vector2d::Zero();
      for (int k = 0; k < 2; ++k)
        if (d_.eq[2 * a + k] >= 0) v(k) = c.mode(d_.eq[2 * a + k]);
      peak = std::max(peak, v.norm());
    }
    const double amplitude_mm = knobs_.stepping.branch_switch * mesh_quality(m_).shortest_side_mm;
    for (const double sign : {1.0, -1.0}) {
      kick_ = Eigen::VectorXd::Zero(2 * nn_);
      for (int i = 0; i < 2 * nn_; ++i)
        if (d_.eq[i] >= 0) kick_(i) = sign * amplitude_mm / peak * c.mode(d_.eq[i]);
      const bool carried = increment(target);
      kick_.resize(0);
      if (carried) {
        out_.branch_switches++;
        return true;
      }
      note << (sign > 0 ? "; + the mode (" : ", − the mode (") << amplitude_mm << " mm) residual " << last_.residual
           << " N/mm";
    }
    branch_note_ = note.str() + ": no branch carried the increment";
    return false;
  }

  // The tangent's critical mode at the increment's start (the converged q with the prescribed
  // motion at `target`, the step from the committed states), as `diagnose` reads it.
  detail::CriticalMode mode_at_start(double target) {
    rotate_bases(target);
    const double dt = time_at(target) - time_at(lambda_);
    assembler_.set_step(states_.committed.data(), scratch_.data(), dt);
    assembler_.begin(q_, target, dt);
    Eigen::VectorXd r;
    if (assembler_.run(prescribed_at(target), target, nullptr, r, &pattern_, nullptr) >= 0) return {};
    return detail::critical_mode(pattern_.K);
  }

  // Stresses, displacements and reactions at the converged q: the last assembly's, which was there
  // (Newton's invariant; the trial states committed after it are its own).
  void snapshot(StaticSolution& s) {
    s.points = assembler_.last_points();
    const Eigen::VectorXd& r = newton_.residual();
    s.u_mm.resize(nn_);
    s.reaction_N_mm.assign(nn_, Eigen::Vector2d::Zero());
    for (int a = 0; a < nn_; ++a) {
      s.u_mm[a] = assembler_.u_of(q_, a);
      Eigen::Vector2d rl = r.segment<2>(2 * a);
      for (int k = 0; k < 2; ++k)
        if (d_.eq[2 * a + k] >= 0) rl(k) = 0.0;
      s.reaction_N_mm[a] = d_.R[a] * rl;
    }
    s.inertia_N_mm.clear();
    for (int a = 0; inertia_ && a < nn_; ++a)
      s.inertia_N_mm.push_back(assembler_.moves(a) ? inertia_->force(a, s.u_mm[a]) : Eigen::Vector2d::Zero());
    s.following_N_mm = assembler_.point_load_forces(q_);
  }

  // Turn the constrained bases to λ = target, keeping the displacements.
  void rotate_bases(double target) {
    if (!p_.motion->has_frame()) return;
    p_.motion->angles(target, angles_);
    for (std::size_t c = 0; c < p_.constraints.size(); ++c) {
      const int n = p_.constraints[c].node;
      const Eigen::Vector2d u = d_.R[n] * q_.segment<2>(2 * n);
      d_.R[n] << std::cos(angles_[c]), -std::sin(angles_[c]), std::sin(angles_[c]), std::cos(angles_[c]);
      q_.segment<2>(2 * n) = d_.R[n].transpose() * u;
    }
  }

  // Per free dof, (Q(θ) − I − θJ)(x − c) of its node's frame turn to λ = target (local components,
  // bases already turned), x the converged position: what the linear predictor leaves out of a
  // finite rotation.
  Eigen::VectorXd rotation_terms(double target) {
    p_.motion->frame_turn(lambda_, target, turns_);
    Eigen::VectorXd extra = Eigen::VectorXd::Zero(2 * nn_);
    for (int a = 0; a < nn_; ++a) {
      const double th = turns_[a].angle_rad;
      const Eigen::Vector2d r = m_.X[a] + assembler_.u_of(q_, a) - turns_[a].centre_mm;
      const Eigen::Vector2d second_order = (std::cos(th) - 1.0) * r + (std::sin(th) - th) * Eigen::Vector2d(-r.y(), r.x());
      const Eigen::Vector2d local = d_.R[a].transpose() * second_order;
      for (int k = 0; k < 2; ++k)
        if (d_.eq[2 * a + k] >= 0) extra(2 * a + k) = local(k);
    }
    return extra;
  }

  // An attempt's work, added to the run's.
  void tally(const NewtonOutcome& attempt) {
    out_.newton_iterations += attempt.iterations;
    out_.factorizations += attempt.factorizations;
    out_.assemblies += attempt.assemblies;
    out_.residual_only_assemblies += attempt.residual_only;
  }

  // One increment to `target`: true (states committed) when Newton converged, else q restored.
  bool increment(double target) {
    rotate_bases(target);
    const Eigen::VectorXd q_saved = q_;
    if (kick_.size() == q_.size()) q_ += kick_;  // a branch switch's start (switch_branch)
    const double dt = time_at(target) - time_at(lambda_);
    assembler_.set_step(states_.committed.data(), states_.trial.data(), dt);
    assembler_.begin(q_, target, dt);
    // Start: the free dofs extrapolated from the last increment (capped at its size, the history
    // turns at transitions); or, first and after a cut, the linear predictor K_fp·Δq_p on a fresh
    // tangent.
    Eigen::VectorXd q_start = prescribed_at(target);
    const bool extrapolate = (knobs_.stepping.extrapolate_start || (knobs_.newton.reuse_tangent && have_factor_)) &&
                             cuts_in_row_ == 0 && velocity_.size() == q_.size();
    if (extrapolate) {
      const double ratio = std::min(1.0, (target - lambda_) / last_dlambda_);
      for (int i = 0; i < 2 * nn_; ++i)
        if (d_.eq[i] >= 0) q_start(i) += ratio * velocity_(i);
    }
    const bool rotated = knobs_.stepping.rotated_predictor && p_.motion->has_frame() && !extrapolate;
    Eigen::VectorXd rotation = rotated ? rotation_terms(target) : Eigen::VectorXd();
    // Without terms this small the retake starts where this try did, to within Newton's first
    // correction: measured, such retakes never converged where the try had not (docs/segment.md
    // §Cost, "Retakes that cannot help").
    const bool retake = rotated && rotation.norm() > kRetakeRotation_mm;
    newton_.set_rotation(std::move(rotation));
    last_ = newton_.solve(target, q_start, extrapolate);
    if (retake && !last_.converged) {  // retaken on the plain linear predictor before a cut
      tally(last_);
      q_ = q_saved;
      newton_.set_rotation(Eigen::VectorXd());
      last_ = newton_.solve(target, q_start, false);
    }
    tally(last_);
    have_factor_ = have_factor_ || last_.factorizations > 0;
    if (!last_.converged) {
      q_ = q_saved;
      return false;
    }
    if (!p_.observers.empty()) {
      StaticSolution view;
      snapshot(view);
      view.increments = out_.increments + 1;
      for (IncrementObserver* observer : p_.observers) observer->converged(target, view);
    }
    states_.committed.swap(states_.trial);  // the last assembly was at the converged q
    assembler_.commit(q_, target);          // the loads' histories (prepared at target by that assembly)
    velocity_ = q_ - q_saved;
    last_dlambda_ = target - lambda_;
    lambda_ = target;
    out_.increments++;
    out_.final_residual = last_.residual;
    cuts_in_row_ = 0;
    if (knobs_.stepping.growth_iterations <= 0 || last_.iterations <= knobs_.stepping.growth_iterations)
      max_step_ = std::min(2.0, 2.0 * max_step_);  // a cut step grows back after an easy success
    return true;
  }

  const StaticProblem& p_;
  const SolverKnobs& knobs_;
  const Mesh& m_;
  Dofs d_;
  std::vector<double> angles_;
  detail::WorkerPool pool_;
  std::unique_ptr<detail::BackwardEulerInertia> inertia_;  // PhysicsOptions::inertia (null: off)
  Assembler assembler_;
  StateBlock states_;
  std::vector<double> scratch_;
  LinearSolver linear_;
  Pattern pattern_;
  const int nn_;
  Eigen::VectorXd q_;
  Newton newton_;
  std::vector<std::array<double, 2>> values_;
  StaticSolution out_;
  NewtonOutcome last_;
  double lambda_ = 0.0, max_step_ = 2.0, uncut_step_ = 2.0, last_dlambda_ = 0.0;
  int cuts_in_row_ = 0;
  bool have_factor_ = false;
  Eigen::VectorXd velocity_;  // Δq of the last converged increment (local components)
  Eigen::VectorXd kick_;      // added to the next increment's start (switch_branch; empty: none)
  std::string branch_note_;   // the last branch switch's finding, for the exit-4 message
  std::vector<FrameTurn> turns_;
};

}  // namespace

int solver_threads(const SolverKnobs& knobs) {
  if (knobs.threads > 0) return knobs.threads;
  return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 2u));
}

StaticSolution solve_static(const StaticProblem& p, const SolverKnobs& knobs) {
  if (!p.mesh || !p.laws[0] || !p.laws[1] || !p.motion)
    throw core::UsageError("solve_static: mesh, both laws and the prescribed displacements are required");
  if (knobs.threads < 0) throw core::UsageError("solve_static: threads must be >= 1, or 0 for the default");
  return StaticRun(p, knobs).run();
}

}  // namespace fitlib::segment
