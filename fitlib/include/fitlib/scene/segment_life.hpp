#pragma once
// Life from the segment FE, orchestrated here (scene): load cycle → segment driven by it
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

namespace fitlib::scene {

// The monitored histories of a segment run as fatigue input: local stresses (1 radial,
// 2 longitudinal), the role from the element's material.
std::vector<fatigue::PointHistory> segment_point_histories(const segment::CycleResult& run);

// The life's default mesh, both levels: 1.0 mm central (one pitch), 2.5 mm ends (one pitch each),
// one cushion row, graded to 0.3 mm columns and thinner rows at the central gap bottom, 192
// elements. Read with a point's stress averaged over the elements that share it (segment::locate),
// its N1 is 0.76–1.01× and its N2 0.93–1.02× those of 0.35–0.6 mm elements on the light, medium and
// heavy drives at the complete level (docs/decisions.md "Segment: a point's stress is averaged over
// the elements that share it"); graded because N1 is read at the gap bottom (docs/decisions.md
// "Segment: the life mesh is graded towards the gap bottom").
segment::MeshKnobs life_mesh();

// The life's load-cycle knobs at a fidelity: CycleKnobs' defaults with the sheared end faces, which
// bring the short life mesh's lives near a long segment's (docs/decisions.md "Segment life: sheared
// end faces"), and at the complete level 120 steps per cycle: its points carry history (rates,
// damage), and 120 planned steps read its lives within 2.5 % of 240 (60: N1 +14 %) at less work
// than 60 with dense increments at the load fronts (docs/decisions.md "Segment life: the complete
// level takes 120 steps per cycle and no load fronts").
segment::CycleKnobs life_cycle(core::Fidelity fidelity = core::Fidelity::elastic);

struct SegmentLifeSetup {
  segment::CogSection section;
  segment::MeshKnobs mesh = life_mesh();
  segment::SolverKnobs solver;
  segment::CycleKnobs cycle = life_cycle();
  std::array<model::MaterialPointPtr, 2> materials;  // by core::MaterialRole: bottom, cushion
  // Optional, per element of the mesh (empty: none; null: the role's): an element's own point
  // (segment::CyclePhysics::element_laws), the elastic level's card read at that element's amplitude.
  std::vector<model::MaterialPointPtr> element_materials;
  std::vector<segment::NamedPoint> extra_points;
  double temperature_C = 20.0;
  fatigue::PeakOptions peaks;
};

struct SegmentLife {
  fatigue::LifeReport report;
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
fatigue::LifeConditions segment_conditions(const belt::LoadCycle& cycle, const belt::DriveCase& drive, double temperature_C,
                                  const segment::CycleResult& run);

// InputError for a standing belt or a drive without a load cycle; NumericalError (exit 4) when
// the segment's Newton fails, naming increment and element.
SegmentLife segment_life(const belt::LoadCycle& cycle, const belt::DriveCase& drive, const SegmentLifeSetup& setup,
                         const fatigue::FatigueCard& card);

}  // namespace fitlib::scene
