#pragma once
// The segment driven by the load cycle, as Report I §5–§6 (belt-mechanics.md §5; docs/segment.md
// §"Loading by the load cycle"). The reference is the section as moulded: the straight mesh
// wrapped on the mould radius (stress-free). Step 1 bends it straight and applies the cycle's
// start state (F1 + F_c as ε = F/c, the free-span curvature); step 2 runs N load cycles from the
// middle of the slack span. At pseudo time τ the cord line is the curve whose curvature and strain
// at unstrained offset ξ from the segment's middle are K(s0 + ξ), F(s0 + ξ)/c of the load history
// (s0 = (τ − 1) L), and the cord-line nodes are placed on it. Where the section is in a sheave
// (p > 0) contact pressure, friction and radial inertia act as body forces (6.6–6.9).
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "fitlib/belt/load_history.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/section.hpp"
#include "fitlib/segment/solver.hpp"
#include "fitlib/segment/static_case.hpp"

namespace fitlib::segment {

struct CycleDrive {                     // what the body forces need beyond the history
  const belt::LoadHistory* history = nullptr;
  double wedge_half_angle_rad = 0.0;    // β
  double width_mm = 11.1542;            // B
  double density_kg_m3 = 1200.0;        // ρ
  double speed_mm_s = 0.0;              // V (> 0)
  double temperature_C = 20.0;
  double friction = 0.0;                // the drive's μ: the stick's available friction (CyclePhysics::flank_stick_N_mm4)
};

// The run's knobs split by concern (issue 32 item 3), as SolverKnobs is: where the increments go
// (CycleStepping), what the cycle models beyond the laws and the drive (CyclePhysics), and what is
// recorded or reported beside the named points (CycleOutputs). Each default is the life's unless
// scene::life_cycle says otherwise.

// Stepping over the load cycle: how many cycles, how many increments and where they are placed.
struct CycleStepping {
  int cycles = 2;
  int steps_per_cycle = 60;             // increments per load cycle (placed where K and p change)
  // Increments of each cycle before the last (0: steps_per_cycle). The life reads the last cycle;
  // the ones before only bring the points' memory to it, so their discretisation reaches the life
  // through that state alone (docs/decisions.md "Segment: the complete level's conditioning cycles
  // at 60 steps").
  int conditioning_steps = 0;
  int bend_steps = 4;                   // increments of step 1
  double change_weight = 4.0;           // share of the steps placed by change of K and p vs uniform
  // Optional: step 2's increments end where the segment's middle reaches these path positions
  // (mm from the start of cycle 1, increasing) instead of the planned ones, and the run stops at
  // the last (a few increments at a transition, of any size; `cycles` is then unused).
  std::vector<double> positions_mm;
  // A run whose points and loads carry no history (no state in any law, no inertia, no tangential
  // flank) starts every load cycle from the same state, so cycle 2 onwards repeat cycle 1 to the
  // Newton tolerance: solve the bend and one cycle, and copy its samples and load totals to the
  // later cycles, shifted by the period (docs/segment.md "Cost (reference)"; off: solve every cycle).
  // The run's increment and iteration counts are then those solved.
  bool repeat_history_free_cycle = true;
  // Such a run's one cycle solved as two halves at once, the second from its own bend to the state
  // at a planned increment in a span (no state depends on the path to it), each half on one thread
  // of the element loop (docs/segment.md "Cost (reference)"; off: in one piece). Lives within 10⁻⁹ of
  // the cycle in one piece; the counts add the second half's bend.
  bool split_history_free_cycle = true;
};

// The physics of the cycle: the mould, the contact body force's sampling, the flank laws, the end
// faces and per-element laws.
struct CyclePhysics {
  double manufactured_radius_mm = 0.0;  // 0 = straight mould (no straightening stress)
  // Each element's contact body force is the mean of 6.6–6.9 over its path extent, sampled every
  // `body_force_sampling_mm` (0 = at its centre only): the force then moves continuously in time
  // when a pulley's exit passes, instead of switching an element at a time (docs/segment.md
  // "The gap bottom's exit peak").
  double body_force_sampling_mm = 0.1;
  // The deformation-limited flank (segment/flank.hpp, docs/segment.md "Flank foundation"): where
  // the section is in a sheave (p > 0, by the share of each element's path extent) the radial
  // contact force also follows each point's depth below the cord curve, B_r = B_r,dead + k (h − h_ref),
  // with this k (N/mm⁴; 0: off, Report I's dead loads alone).
  double flank_stiffness_N_mm4 = 0.0;
  // The tangential flank (segment/flank.hpp, docs/segment.md "Tangential flank"): where the load
  // cycle uses less friction than the drive's μ (CycleDrive::friction), each point's motion along
  // the cord relative to its column's cord point is held by an elastic stick of this k_t (N/mm⁴),
  // up to the unused friction (μ − μ_used) p 2/(B cos β), then slips; added to 6.6 (0: off,
  // Report I's dead friction alone).
  double flank_stick_N_mm4 = 0.0;
  // The sliding friction's direction (segment/flank.hpp, docs/segment.md "Tangential flank"): Report
  // I's friction 6.6–6.7 turned to oppose the sliding velocity V ê + u̇, V the load cycle's sliding
  // speed (at least this floor, mm/s, where it is smaller: the non-sliding arc) and u̇ each point's
  // velocity relative to its column's cord point, backward Euler over the increment (0: off,
  // Report I's dead friction).
  double flank_slide_floor_mm_s = 0.0;
  // The friction turned by the flank's compliance (segment/flank.hpp, docs/segment.md "Tangential
  // flank"): Coulomb's friction of Report I's magnitude, its direction turned by each point's motion
  // along the cord relative to its column's cord point through an elastic layer of this k_t (N/mm⁴),
  // the turn relaxed by the load cycle's sliding (0: off, Report I's dead friction).
  double flank_turn_N_mm4 = 0.0;
  // Whether a flank law acts along the belt (it then carries history: the offsets it commits).
  bool flank_along_belt() const {
    return flank_stick_N_mm4 > 0.0 || flank_slide_floor_mm_s > 0.0 || flank_turn_N_mm4 > 0.0;
  }
  // The end faces: radial (planes on the cord's normals), free, or sheared: radial faces warped and
  // sheared like a long belt's sections (segment/end_faces.hpp; the life's default, scene::life_cycle).
  EndCondition ends = EndCondition::radial;
  // Optional, instead of the sheared condition's model (e.g. a longer run's sections, sub-modelling):
  // σ12 (MPa, the cord curve's local frame) on the end faces and their warping (mm along the cord
  // tangent from the radial line) at depth h below the cord line while the segment's middle is at
  // path position s; side 0 left, 1 right. The shear acts along the end's radial line.
  using EndProfile = std::function<double(int side, double depth_mm, double s_mm)>;
  EndProfile end_shear_MPa, end_warping_mm;
  // Optional, per element of build_mesh's mesh (empty: none): a law replacing laws[role] for that
  // element (nullptr: the role's; StaticProblem::element_laws). Each must carry no history and give
  // its role law's symmetric_tangent() (UsageError otherwise).
  std::vector<const PlaneStrainLaw*> element_laws;
};

// What the run records or reports beside the named points' histories: progress, VTK fields, the
// design regions' scan and the element means.
struct CycleOutputs {
  // Called after each converged increment with the share of the run done (0–1: the bend, then the
  // cycles): a long run's progress.
  std::function<void(double done)> progress;
  // Full-field stress (VTK, cell means, global x–y) when the segment's middle first reaches each
  // path position of the last cycle: <vtk_prefix>-<k>.vtk. Empty prefix: none.
  std::vector<double> vtk_at_s_mm;
  std::string vtk_prefix;
  // The design regions' scan (Report I §6.4, L1020–1030; docs/segment.md "Design points by
  // scanning"): every integration point of the bottom rubber between the central cogs (the gap's
  // land and root fillets, |x| ≤ land half-width + root fillet), the gap's surface nodes over the
  // same width, and the cushion's mid-depth below each element centre of the central section,
  // recorded like the named points into CycleResult::scanned (off: the named points alone).
  bool scan_design_regions = false;
  // Each element's mean over its integration points (stresses and logarithmic strains in the cord
  // curve's local frame at its centre's path position), recorded like a named point into
  // CycleResult::element_means (named "e<k>", at its centre): the strain each element reached, which the
  // elastic level reads its cards at (docs/segment.md "One secant per element").
  bool record_elements = false;
};

struct CycleKnobs {
  CycleStepping stepping;
  CyclePhysics physics;
  CycleOutputs outputs;
};

struct CycleSample {                    // a monitored point at the end of an increment
  double t_s = 0.0, s_mm = 0.0;         // time, path position of the segment's middle
  double s11_MPa = 0.0, s22_MPa = 0.0, s12_MPa = 0.0, s33_MPa = 0.0;  // local: 1 radial, 2 along
  double e11 = 0.0, e22 = 0.0, e12 = 0.0;  // logarithmic strain, same frame (e12 tensor shear)
};

struct MonitoredHistory {
  NamedPoint point;
  Role role = Role::bottom;
  // The named point in the (moulded) reference mesh: its stresses are interpolated there from its
  // element's integration points, as `stress_at` does for the static cases.
  PointLocation at;
  Eigen::Vector2d X_mm = Eigen::Vector2d::Zero();
  // A scanned integration point (CycleOutputs::scan_design_regions): its element's rule index and
  // the point's own stresses, not interpolated (−1: a named point or a scanned surface node).
  int gauss_point = -1;
  std::vector<CycleSample> samples;
};

struct IncrementLoads {                // totals per mm of width at the end of an increment, global x–y
  double t_s = 0.0, s_mm = 0.0;
  Eigen::Vector2d cord_reaction_N_mm = Eigen::Vector2d::Zero();  // Σ reactions of the cord-line nodes
  Eigen::Vector2d body_force_N_mm = Eigen::Vector2d::Zero();     // ∫ b dV (contact, friction, inertia)
  // Along the cord tangent at the segment's middle (N/mm): the belt force F/B of the history there,
  // the cord line's reactions (all; left of the middle), the left end face's (without the cord
  // node), and the rubber's section force through the mid-section (docs/segment.md "Cord-line
  // reactions and the belt force").
  double belt_force_N_mm = 0.0, cord_longitudinal_N_mm = 0.0, left_cord_longitudinal_N_mm = 0.0;
  double left_end_longitudinal_N_mm = 0.0, rubber_section_N_mm = 0.0;
  double left_inertia_longitudinal_N_mm = 0.0;  // Σ m·a of the left half's nodes (PhysicsOptions::inertia)
  // Radial totals (along the cord curve's outward normal at each element's centre) of Report I's
  // dead contact load, Σ B_r dV, and of the flank foundation, Σ ∫ b·n dV (CyclePhysics::flank_stiffness_N_mm4;
  // both 0 when the foundation is off: they feed flank_shares only).
  double contact_radial_N_mm = 0.0, flank_radial_N_mm = 0.0;
  // The same along the cord tangent: Report I's dead 6.6–6.9 and the flank's (its stick; 0 without one).
  double contact_longitudinal_N_mm = 0.0, flank_longitudinal_N_mm = 0.0;
  bool span = false;  // in a span: no contact load (p = 0) and one curvature (to 10⁻⁶/mm) on every element
};

// The built-in equilibrium check's bounds (docs/segment.md "Cord-line reactions and the belt
// force"): what the tests hold a run to and what `fitcli life` warns beyond.
struct EquilibriumBounds {
  static constexpr double equilibrium_error = 1e-6;      // |Σ reactions + ∫ b dV| / Σ magnitudes
  static constexpr double span_cord_share = 1e-5;        // |Σ cord-line reactions along| / (F/B)
  // With history-dependent points (the complete level) the rubber relaxes in a span and passes
  // stress to the cord line: "small compared with the total belt force" (Fritzson §5), measured
  // 0.8–1.0·10⁻³ (docs/segment.md "Cord-line reactions and the belt force").
  static constexpr double span_cord_share_with_history = 1e-2;
  // With sheared end faces (the life's default) the faces carry the long belt's shear, which decays
  // over a few shear-lag lengths beyond a pulley, into the first span increments; measured
  // 1.2·10⁻⁵–5.4·10⁻⁴ on the reference drives (docs/segment.md "End faces").
  static constexpr double span_cord_share_sheared_ends = 1e-2;
  static constexpr double span_section_mismatch = 1e-6;  // the left half's longitudinal balance
};

struct CycleResult {
  std::vector<MonitoredHistory> points;
  std::vector<MonitoredHistory> scanned;  // CycleOutputs::scan_design_regions, element by element
  std::vector<MonitoredHistory> element_means;  // CycleOutputs::record_elements: one per element, in mesh order
  double cycle_time_s = 0.0;
  // Built-in equilibrium check: the largest |Σ reactions + ∫ b dV| over all increments, relative
  // to Σ |nodal reactions| + Σ |element body forces| (at the Newton tolerance when all is right).
  double equilibrium_error = 0.0;
  double max_cord_reaction_N_mm = 0.0;  // largest |Σ cord-line reactions| (per mm of width)
  // Largest |Σ cord-line reactions along the belt| / (F/B) over the increments in the spans: the
  // thesis's "additional reaction forces at the neutral layer", small against the belt force.
  double span_cord_share = 0.0;
  // Largest |left end face + left cord reactions + rubber section force| / |rubber section force|
  // over the span increments: the left half's longitudinal balance at the mid-section.
  double span_section_mismatch = 0.0;
  std::vector<IncrementLoads> loads;    // per converged increment
  // The flank foundation's radial total against Report I's dead one, over the increments whose dead
  // radial load is at least half its largest: the ratio of largest magnitude (signed) and the mean
  // ratio (flank_shares; 0 without the foundation).
  double flank_radial_share = 0.0, flank_radial_mean_share = 0.0;
  double flank_stiffness_N_mm4 = 0.0;  // the run's CyclePhysics::flank_stiffness_N_mm4
  // The stick (CyclePhysics::flank_stick_N_mm4): its k_t, and its largest |Σ ∫ b·t dV| over the
  // increments (along the cord tangent at each element's centre, N/mm) against the largest
  // |Σ B_l dV| of Report I's dead friction over the run (0 without the stick).
  double flank_stick_N_mm4 = 0.0, flank_stick_share = 0.0;
  std::vector<std::string> vtk_files;   // written, in the order of vtk_at_s_mm
  // The last cycle's stress work ∮ P : dF over the central two pitches per mm of belt length, per
  // role (bottom, cushion): the energy the rubber dissipates per cycle, J/mm (docs/thermal.md §1).
  std::array<double, 2> dissipation_J_mm{};
  int increments = 0, newton_iterations = 0, factorizations = 0, cuts = 0, elements = 0, equations = 0;
  bool history = false;  // a role's law carries state (viscoelastic, damage): EquilibriumBounds' looser span share
  bool sheared_ends = false;  // end faces warped and sheared (EndCondition::sheared or given profiles)
  StaticSolution final_state;
};

// CycleResult::flank_radial_share and flank_radial_mean_share from its loads.
void flank_shares(CycleResult& run);

// The span share's bound of a run: EquilibriumBounds' tight one, or the looser one when its points
// carry history or its end faces are sheared.
double span_cord_share_bound(const CycleResult& run);

// The planned increments of each cycle before the last (conditioning_steps, else steps_per_cycle).
int conditioning_increments(const CycleStepping& stepping);
// The run's planned increments: the bend's, then each cycle's.
int planned_increments(const CycleStepping& stepping);

// The increments' τ of step 2 over one cycle: `steps` breakpoints at equal shares of the measure
// 1/L + w (|dK/ds|/TV(K) + |dp/ds|/TV(p)) — fine where curvature or pressure change — with each
// change spread over ±reach_mm (the segment's half-length: it feels a change before its middle
// reaches it).
std::vector<double> cycle_breakpoints(const belt::LoadHistory& history, int steps, double change_weight,
                                      double reach_mm = 0.0);

// Body force (N/mm³, local: along the belt l and radial outward r) at a load state, 6.6–6.7.
Eigen::Vector2d contact_body_force(const belt::LoadState& state, const CycleDrive& drive);

CycleResult run_cycle(const CogSection& section, const MeshKnobs& mesh_knobs, const SolverKnobs& solver,
                      const std::array<const PlaneStrainLaw*, 2>& laws, const CycleDrive& drive,
                      const CycleKnobs& knobs, const std::vector<NamedPoint>& extra_points = {});

// CSV of the monitored histories: point, role, t_s, s_mm, s11, s22, s12, s33, e11, e22, e12.
void write_cycle_csv(const CycleResult& result, const std::string& path);

}  // namespace fitlib::segment
