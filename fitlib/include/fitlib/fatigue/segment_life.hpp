#pragma once
// Life from the segment FE (issue 11 items 1–2 joined): load cycle → segment driven by it
// (segment/cycle.hpp) → stress histories at the monitored points → fatigue life. One library call
// the scene planner runs for the `elastic` and `complete` fidelities; the beam level is
// beam_section.hpp.
#include <array>
#include <vector>

#include "fitlib/belt/load_cycle.hpp"
#include "fitlib/fatigue/life.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/segment/cycle.hpp"
#include "fitlib/segment/point_law.hpp"

namespace fitlib::fatigue {

// The monitored histories of a segment run as fatigue input: local stresses (1 radial,
// 2 longitudinal), the role from the element's material.
std::vector<PointHistory> segment_point_histories(const segment::CycleResult& run);

// The life's default mesh: 1.0 mm central (one pitch), 2.5 mm ends (one pitch each), one cushion
// row, graded to 0.3 mm columns and thinner rows at the central gap bottom, 192 elements; N1 there
// within 8 % of uniform 0.25–0.4 mm meshes (docs/decisions.md "Segment: the life mesh is graded
// towards the gap bottom").
segment::MeshKnobs life_mesh();

// The complete level's default mesh: the life mesh with three equal cushion rows and no column
// grading (gap_size_mm 0; rows still thin by row_growth 1.1 towards the land), 180 elements. One
// cushion row lets the complete level's glassy, near-incompressible cushion carry a spurious
// pressure gradient through the row at the driver's exit (mid-cushion σ11 +0.5 MPa where three or
// more rows give −0.35 MPa), which made N2 ~800× short and separation govern on the light drive;
// with three rows N2 is within 12 % of every finer mesh tried, N1 as short as the graded 1 mm
// mesh's (the complete level's N1 is not settled by the element size), at 1.13–1.17× the one-row
// mesh's time (docs/decisions.md "Segment life: the complete level's mesh has three cushion rows";
// docs/segment.md "Which segment N1 should be read from").
segment::MeshKnobs complete_life_mesh();

// The life's default mesh at a fidelity: life_mesh() (elastic) or complete_life_mesh() (complete).
segment::MeshKnobs life_mesh(segment::Fidelity fidelity);

// The life's Newton step control at a fidelity, on `knobs`: at the complete level (points with
// history, where a quarter of the iterations went into attempts that failed) a stall after 6
// assemblies instead of 8 and a cut step grown back only after an increment that converged within
// 5 assemblies: 13 % fewer iterations on the light drive, lives within 0.3 % (docs/decisions.md
// "Segment life: the complete level's step control"); the elastic level keeps the solver's defaults,
// which the stall of 6 would cost 6.5 % on the heavy drive.
segment::SolverKnobs life_solver(segment::Fidelity fidelity, segment::SolverKnobs knobs = {});

// The life's load-cycle knobs: CycleKnobs' defaults with the sheared end faces, which bring the
// short life mesh's lives near a long segment's (docs/decisions.md "Segment life: sheared end faces").
segment::CycleKnobs life_cycle();

struct SegmentLifeSetup {
  segment::CogSection section;
  segment::MeshKnobs mesh = life_mesh();  // the elastic level's; the scene takes life_mesh(fidelity)
  segment::SolverKnobs solver;
  segment::CycleKnobs cycle = life_cycle();
  std::array<model::MaterialPointPtr, 2> materials;  // by segment::Role: bottom, cushion
  std::vector<segment::NamedPoint> extra_points;
  double temperature_C = 20.0;
  PeakOptions peaks;
};

struct SegmentLife {
  LifeReport report;
  segment::CycleResult run;
  double wall_s = 0.0;
};

// The work of a segment run in element-increments: the mesh's elements × (bend steps + cycles ×
// steps per cycle), the nominal increments (cuts add more). Its cap is the scene's
// (docs/reliability.md §4, "[life] cycles × mesh elements × steps").
double segment_run_work(const SegmentLifeSetup& setup);

// The segment driven by the load cycle (no life): what segment_life evaluates.
segment::CycleResult segment_run(const belt::LoadCycle& cycle, const belt::DriveCase& drive,
                                 const SegmentLifeSetup& setup);

// The life conditions of a segment run: the load cycle's (cycle_conditions), with the run's cycle
// time, so that only its last simulated cycle counts (fatigue.md §3; the bending step and the
// earlier cycles are the transient).
LifeConditions segment_conditions(const belt::LoadCycle& cycle, const belt::DriveCase& drive, double temperature_C,
                                  const segment::CycleResult& run);

// InputError for a standing belt or a drive without a load cycle; NumericalError (exit 4) when
// the segment's Newton fails, naming increment and element.
SegmentLife segment_life(const belt::LoadCycle& cycle, const belt::DriveCase& drive, const SegmentLifeSetup& setup,
                         const FatigueCard& card);

}  // namespace fitlib::fatigue
