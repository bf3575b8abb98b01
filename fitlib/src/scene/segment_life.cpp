// Life from the segment FE (fitlib/scene/segment_life.hpp).
#include "fitlib/scene/segment_life.hpp"

#include <chrono>

#include "fitlib/belt/load_history.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/fatigue/beam_section.hpp"
#include "fitlib/segment/point_law.hpp"

namespace fitlib::scene {

segment::MeshKnobs life_mesh() {
  segment::MeshKnobs m;
  m.fine_size_mm = 1.0, m.coarse_size_mm = 2.5, m.central_pitches = 1.0, m.end_pitches = 1.0, m.cushion_rows = 1;
  // Graded at the gap bottom, where N1 is read (docs/decisions.md "Segment: the life mesh is graded
  // towards the gap bottom"): 0.3 mm columns growing by 0.25 mm per mm, rows thinning by 1.1.
  m.gap_size_mm = 0.3, m.column_growth = 0.25, m.row_growth = 1.1;
  return m;
}

segment::CycleKnobs life_cycle(core::Fidelity fidelity) {
  segment::CycleKnobs c;
  c.physics.ends = segment::EndCondition::sheared;
  // The complete level's cycles before the last at half the steps: they only bring the points'
  // memory to the cycle the life reads (docs/decisions.md "Segment: the complete level's
  // conditioning cycles at 60 steps").
  if (fidelity == core::Fidelity::complete) c.stepping.steps_per_cycle = 120, c.stepping.conditioning_steps = 60;
  return c;
}

std::vector<fatigue::PointHistory> segment_point_histories(const segment::CycleResult& run) {
  std::vector<fatigue::PointHistory> out;
  for (const auto* histories : {&run.points, &run.scanned})  // named first: they win a tie
    for (const segment::MonitoredHistory& m : *histories) {
      const bool scanned = histories == &run.scanned;
      fatigue::PointHistory p;
      p.name = m.point.name;
      p.role = m.role;
      p.x_mm = m.point.x_mm, p.y_mm = m.point.y_mm;
      if (scanned) p.element = m.at.element, p.integration_point = m.gauss_point;
      for (const segment::CycleSample& c : m.samples)
        p.samples.push_back({c.t_s, c.s11_MPa, c.s22_MPa, c.s12_MPa, c.e11, c.e22, c.e12});
      out.push_back(std::move(p));
    }
  return out;
}

double segment_run_work(const SegmentLifeSetup& setup) {
  const double elements = segment::build_mesh(setup.section, setup.mesh).element_count();
  return elements * segment::planned_increments(setup.cycle.stepping);
}

segment::CycleResult segment_run(const belt::LoadCycle& cycle, const belt::DriveCase& drive,
                                 const SegmentLifeSetup& setup) {
  if (!setup.materials[0] || !setup.materials[1])
    throw core::UsageError("segment life: a material point per role (bottom, cushion) is required");
  fatigue::cycle_conditions(cycle, drive, setup.temperature_C);  // refuses a standing belt before the FE runs
  const belt::LoadHistory history(cycle, drive.belt, setup.temperature_C);
  segment::CycleDrive d;
  d.history = &history;
  d.wedge_half_angle_rad = drive.belt.wedge_half_angle_rad;
  d.width_mm = drive.belt.width_mm;
  d.density_kg_m3 = drive.belt.density_kg_m3;
  d.speed_mm_s = drive.belt_speed_mm_s;
  d.temperature_C = setup.temperature_C;
  d.friction = drive.friction;
  const segment::ContractLaw bottom(setup.materials[0]), cushion(setup.materials[1]);
  if (setup.element_materials.empty())
    return segment::run_cycle(setup.section, setup.mesh, setup.solver, {&bottom, &cushion}, d, setup.cycle,
                              setup.extra_points);
  std::vector<segment::ContractLaw> own;  // one per element with its own point
  own.reserve(setup.element_materials.size());
  segment::CycleKnobs knobs = setup.cycle;
  for (const model::MaterialPointPtr& point : setup.element_materials)
    knobs.physics.element_laws.push_back(point ? &own.emplace_back(point) : nullptr);
  return segment::run_cycle(setup.section, setup.mesh, setup.solver, {&bottom, &cushion}, d, knobs, setup.extra_points);
}

fatigue::LifeConditions segment_conditions(const belt::LoadCycle& cycle, const belt::DriveCase& drive, double temperature_C,
                                  const segment::CycleResult& run) {
  fatigue::LifeConditions c = fatigue::cycle_conditions(cycle, drive, temperature_C);
  c.cycle_time_s = run.cycle_time_s;
  return c;
}

SegmentLife segment_life(const belt::LoadCycle& cycle, const belt::DriveCase& drive, const SegmentLifeSetup& setup,
                         const fatigue::FatigueCard& card) {
  const auto t0 = std::chrono::steady_clock::now();
  SegmentLife out;
  out.run = segment_run(cycle, drive, setup);
  fatigue::LifeConditions conditions = segment_conditions(cycle, drive, setup.temperature_C, out.run);
  conditions.peaks = setup.peaks;
  out.report = fatigue::evaluate_life(segment_point_histories(out.run), card, conditions);
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace fitlib::scene
