#pragma once
// Quasi-static finite-strain solve of a plane-strain mesh (total Lagrangian, unit thickness):
// Newton with the consistent tangent, the Eigen sparse direct solver with the pattern analysed
// once, a backtracking line search and step cutting. Loads grow with a parameter λ from 0 to 1:
// prescribed node displacements (in a per-node rotated basis, so a node can slide along a line)
// and the load objects of segment/load.hpp. A failure throws core::NumericalError naming the
// step, the element and the residual (exit 4).
#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fitlib/segment/elastic.hpp"
#include "fitlib/segment/load.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/observer.hpp"

namespace fitlib::segment {

// 2×2 or 3×3 Gauss (8 nodes; 2×2 for 4 nodes); `fbar`: 3×3 (2×2) with F̄ = (J̄/J)^½ F, J̄ from the
// 2×2 (centre) points — neither locks nor has spurious modes (docs/segment.md §Element choice).
enum class Integration { reduced, full, fbar };

struct NodeConstraint {
  int node = 0;
  double angle_rad = 0.0;           // local basis: e0 = (cos a, sin a), e1 = (−sin a, cos a)
  std::array<bool, 2> fixed{true, true};  // which local components are prescribed
};
// Newton's iterations within one load increment (newton.hpp: the step policy and its named
// constants; docs/segment.md §Solver).
struct NewtonOptions {
  int max_iterations = 30;        // assemblies per increment (Newton iterations and halvings)
  int stall_iterations = 8;       // assemblies without a new lowest residual before a cut
  // A stalled iterate is accepted below this (a point law whose tangent is not exactly consistent,
  // e.g. Fritzson's damage, converges only linearly near round-off; docs/segment.md §Solver).
  double stall_tolerance = 1e-5;
  double tolerance = 1e-9;        // residual / (reaction norm + 1 N/mm)
  // Modified Newton: keep a factorisation while the residual contracts by Newton::kReuseContraction
  // per iteration, and start each increment from the last one's extrapolated motion. Off by
  // default: slower on the load cycle, whose transitions need fresh tangents (docs/segment.md §Cost).
  bool reuse_tangent = false;
  // Levenberg–Marquardt shift (0 = off): a full Newton step that lowers neither the residual nor
  // the energy measure is retaken from its start on K + μ·diag|K|, μ from this value and ×10 per
  // failed retake, then scaled by each step's residual ratio; the line search halves only beyond
  // μ = 10⁴ × this. The residual is not changed, so the solution is Newton's; the shift turns the
  // step towards steepest descent where the tangent is nearly singular, the near-incompressible
  // rubber at the load cycle's transitions; the shift is dropped once the residual is below the
  // retaken step's start (docs/segment.md §Solver, "Levenberg–Marquardt retake").
  double levenberg = 3e-3;
  // Unsymmetric tangents (the complete level, F-bar, follower pressure): GMRES preconditioned with
  // the LDLᵀ of the tangent's symmetric part, up to this many iterations to a preconditioned
  // residual below krylov_tolerance of its start; UMFPACK's LU only when that fails (0: the LU
  // every time; not with reuse_tangent, which keeps the LU for its later steps). Newton's iterations
  // stay those of the exact solve (docs/segment.md §Solver).
  int krylov_iterations = 10;
  double krylov_tolerance = 1e-8;
  // GMRES at an iterate whose residual is below this share of the reaction scale (the `tolerance`'s
  // scale) first runs on the preconditioner factorised for an earlier iterate of the increment, and
  // refactorises only when that does not converge: Newton's iterations stay those of the exact solve,
  // at fewer factorisations (0: a factorisation per tangent; docs/segment.md §Solver, "Kept
  // preconditioner").
  double keep_preconditioner_below = 1e-2;
  // The tangent's pressure term at each point's pressure linearised over the last step (Newton on
  // the mixed u–p form with p condensed per point), not at the new iterate's, whose κ det ΔF is
  // spurious near incompressibility; the residual, and so the solution, unchanged. Not with F-bar
  // nor with reuse_tangent. Complete level: the second correction no longer stagnates, −29 to −35 %
  // iterations (docs/segment.md §"Cost (reference)", 2026-12-04).
  bool linearised_pressure = true;
  // The LDLᵀ (of the tangent, or of its symmetric part for GMRES) in two halves at once, one on each
  // of the element loop's threads, the separator's Schur complement dense between (one level of
  // nested dissection; the same arithmetic on any thread count). Off: one LDLᵀ on the lead thread
  // (docs/segment.md §Solver, "Split LDLᵀ").
  bool split_factorisation = true;
};

// Load stepping over λ from 0 to 1 (solver.cpp): the increments, their cuts and where each starts.
struct SteppingOptions {
  int steps = 4;                  // equal load increments of λ (when `schedule` is empty)
  std::vector<double> schedule;   // increasing λ breakpoints in (0, 1]; 1 is appended
  int max_cuts = 6;               // halvings of an increment before giving up
  // A cut step doubles back only after an increment that converged within this many assemblies
  // (0: after any), as Abaqus grows its increment only after easy ones: one that needed more lies
  // near where the cut was, and a doubled step there fails again (docs/segment.md §Cost).
  int growth_iterations = 0;
  // Start each increment (after a converged one, not after a cut) from the last increment's
  // displacement extrapolated linearly in λ (time), capped at its size; a start that does not
  // converge is retaken from the linear predictor (docs/segment.md §Solver).
  bool extrapolate_start = false;
  // Correct the linear predictor by the second-order part of each node's finite rotation with the
  // loading (PrescribedMotion::frame_turn, when the motion has a frame): a linearised rotation θ
  // strains a near-incompressible rubber by θ²/2 (docs/segment.md §Solver, "Rotated predictor").
  // Off: with NewtonOptions::linearised_pressure the plain linear predictor needs fewer iterations
  // (the R = 40 mm bend 24 against 32, the light drive's complete level 950 against 1025; docs/decisions.md
  // "Segment: the tangent's pressure linearised over the last step").
  bool rotated_predictor = false;
  // Branch switch (0: off): an increment that fails after its last cut, with the lowest eigenvalue
  // of K's symmetric part at its start ≤ 0 (the path has passed a bifurcation), is retaken from its
  // start moved by + and then − the critical mode, scaled so that its largest nodal displacement is
  // this share of the mesh's shortest element side (docs/segment.md §Solver, "Branch switch").
  double branch_switch = 0.0;
};

// What the solve models beyond the problem's laws and loads.
struct PhysicsOptions {
  Integration integration = Integration::reduced;
  // Implicit dynamics (off: quasi-static): the rubber's lumped mass (StaticProblem::density_t_mm3)
  // on the nodes' motion relative to PrescribedMotion::frame_motion, backward Euler in
  // StaticProblem::time_s; tangent K + M/Δt². Lets the load path pass a limit point by a dynamic
  // snap (docs/segment.md "Inertia"; segment/inertia.hpp).
  bool inertia = false;
};

struct SolverKnobs {
  NewtonOptions newton;
  SteppingOptions stepping;
  PhysicsOptions physics;
  // Threads of the element loop (0: min(2, the hardware's)). Each element's response is computed
  // into its own buffer and the buffers are added in element order, so the result is bit-identical
  // whatever the count (docs/segment.md §Solver, "Threads").
  int threads = 0;
  // On failure, check the assembled tangent against central differences of the residual (per
  // element and per integration point) and scan the residual along Newton's direction at the
  // failing increment's best iterate; the findings go into the exit-4 message (docs/segment.md
  // §Solver, "Failure diagnosis"). Costs two residual assemblies per equation, once.
  bool diagnose_failure = false;
};
// The thread count a run with these knobs uses (resolves threads = 0).
int solver_threads(const SolverKnobs& knobs);

struct StaticSolution;

struct StaticProblem {
  const Mesh* mesh = nullptr;
  std::array<const PlaneStrainLaw*, 2> laws{};  // indexed by Role
  std::vector<NodeConstraint> constraints;
  std::shared_ptr<const PrescribedMotion> motion;  // the constraints' values at λ (segment/load.hpp)
  // The loads (segment/load.hpp), each prepared per load level, added after the element loop in
  // this order and committed after each converged increment (not owned beyond the shared pointer).
  std::vector<LoadPtr> loads;
  // Time (s) at load level λ for rate-dependent laws; empty = 0 throughout (a static case
  // applied at once: the glassy response of a viscoelastic law). Temperature of every point.
  std::function<double(double lambda)> time_s;
  // Called in order after every converged increment with its stresses, displacements, reactions
  // (not owned; each must outlive the solve).
  std::vector<IncrementObserver*> observers;
  double temperature_C = std::numeric_limits<double>::quiet_NaN();  // NaN = the cards' reference
  // PhysicsOptions::inertia: mass density (t/mm³ = 10¹² kg/m³); the inertia acts on the motion relative
  // to the prescribed motion's frame (PrescribedMotion::frame_motion; without one, the reference).
  double density_t_mm3 = 0.0;
  // Optional, per element of `mesh` (empty: none): a law that replaces laws[role] for that element
  // (nullptr: the role's). The elastic level reads each element's card at its own strain amplitude
  // this way (docs/segment.md "One secant per element"). Each must give the same symmetric_tangent()
  // as its role's law (the solver chooses its factorisation by the role laws).
  std::vector<const PlaneStrainLaw*> element_laws;
  const PlaneStrainLaw& law_of(int element) const {
    if (!element_laws.empty() && element_laws[static_cast<std::size_t>(element)]) return *element_laws[static_cast<std::size_t>(element)];
    return *laws[static_cast<int>(mesh->roles[static_cast<std::size_t>(element)])];
  }
};

struct IntegrationPointStress {
  Eigen::Vector2d X_mm = Eigen::Vector2d::Zero();          // reference position
  Eigen::Matrix2d cauchy_MPa = Eigen::Matrix2d::Zero();    // global x, y components
  double sigma33_MPa = 0.0;
  Eigen::Matrix2d piola_MPa = Eigen::Matrix2d::Zero();     // first Piola–Kirchhoff (section forces)
  Eigen::Matrix2d F = Eigen::Matrix2d::Identity();         // deformation gradient
};

struct StaticSolution {
  std::vector<Eigen::Vector2d> u_mm;                        // per node, global
  std::vector<Eigen::Vector2d> reaction_N_mm;               // per node (zero where free)
  std::vector<std::vector<IntegrationPointStress>> points;  // per element
  std::vector<double> state;       // all integration points' committed states, one block
  std::vector<std::size_t> state_offset;  // per element, into `state`
  int increments = 0, newton_iterations = 0, cuts = 0, factorizations = 0;
  // Element loops (residual, with the tangent where one is factorised), failed attempts and line
  // search included: the run's other cost beside the factorisations.
  int assemblies = 0;
  // Of them, made without the tangent because they were predicted to show convergence (newton.hpp).
  int residual_only_assemblies = 0;
  int branch_switches = 0;  // increments carried by SteppingOptions::branch_switch
  double final_residual = 0.0;
  int equations = 0;
  int pattern_analyses = 0;       // symbolic analyses of the tangent's sparsity (1 per run; 2 when GMRES fell back to the LU)
  bool symmetric_solver = false;  // LDLᵀ (every law's tangent symmetric, no follower load) or LU
  bool split_factorisation = false;  // the LDLᵀ ran in two halves (NewtonOptions::split_factorisation)
  // PhysicsOptions::inertia: per node, its inertia force m·a (global, N/mm; in the residual as
  // internal − external + inertia, so Σ reactions + external − Σ m·a = 0); empty without inertia.
  std::vector<Eigen::Vector2d> inertia_N_mm;
  // The loads acting at the integration points (Load::at_point): per element, their ∫ b dV
  // (global, N/mm); empty without one.
  std::vector<Eigen::Vector2d> following_N_mm;
  int threads = 1;                // of the element loop
  // Unsymmetric tangents (NewtonOptions::krylov_iterations): GMRES iterations, and the solves that
  // did not converge and went to the LU (`factorizations` counts either factorisation once per tangent).
  int krylov_iterations = 0, krylov_fallbacks = 0;
};

StaticSolution solve_static(const StaticProblem& problem, const SolverKnobs& knobs);

// Internal force the elements with reference centroid x < x_cut exert on the nodes at x = x_cut,
// i.e. the section force transmitted through the cut (N/mm), and its moment about `about`
// (deformed coordinates): M = Σ (y − y0) f_x − (x − x0) f_y (positive when the bottom is compressed).
struct SectionForce {
  Eigen::Vector2d force_N_mm = Eigen::Vector2d::Zero();
  double moment_N = 0.0;  // N·mm/mm
};
SectionForce section_force(const StaticProblem& problem, const StaticSolution& solution, double x_cut_mm,
                           const Eigen::Vector2d& about_mm, Integration integration);

// A reference point's element and isoparametric coordinates (ξ, η) ∈ [−1, 1]², and the other
// elements of the same role that hold it (a node or side they share). Throws core::InputError if
// the point is outside the mesh.
struct ElementPoint {
  int element = -1;
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
};
struct PointLocation {
  int element = -1;
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
  std::vector<ElementPoint> shared;
};
PointLocation locate(const Mesh& mesh, const Eigen::Vector2d& X_mm);

// The integration points' Cauchy stress, σ33, first Piola stress and F of the located element,
// interpolated to the point by Lagrange polynomials through the Gauss points (extrapolated beyond
// the outermost ones, e.g. to a surface), averaged over the elements that share the point (as FE
// post-processors average nodal stresses: one element's extrapolation to its corner carries the
// gradient's one-sided error, docs/segment.md "Stress at a point"); X_mm is the point's reference
// position.
IntegrationPointStress interpolate(const StaticSolution& solution, const PointLocation& at, int gauss_order_1d,
                                   const Eigen::Vector2d& X_mm);

// Cauchy stress at a reference point: locate + interpolate.
Eigen::Matrix2d stress_at(const Mesh& mesh, const StaticSolution& solution, const Eigen::Vector2d& X_mm,
                          Integration integration, double* sigma33_MPa = nullptr);

int gauss_order(const Mesh& mesh, Integration integration);
// Whether the element's tangent is symmetric for a symmetric law tangent (F-bar's is not), so the
// solver may factorise it with LDLᵀ.
bool symmetric_tangent(Integration integration);
Integration integration_from_string(const std::string& name);  // "reduced" | "full" | "fbar"
const char* to_string(Integration integration);

}  // namespace fitlib::segment
