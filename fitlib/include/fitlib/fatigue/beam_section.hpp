#pragma once
// The `beam` fidelity level (issue 11 item 5; docs/fatigue.md §5): layer stresses of the cogged
// section from the load cycle without FE, for sweeps over many drives. At each sample of the
// cycle the monitored points see
//   ε22 = (1 + F/c)(1 − K d)/(1 − K_m d) − 1          (layer stretch below the cord line, depth d)
//   σ11 = −B_r h,  σ12 = B_l h                          (radial and shear load carried above the
//                                                        free bottom, B_r, B_l of (6.6)–(6.7))
//   σ22 = k_t E/(1 − ν²) ε22 + ν/(1 − ν) σ11           (plane strain, σ33 from ε33 = 0)
// with h the loaded height below the point: to the free land surface for the gap centre line
// (σ11 = σ12 = 0 at the gap bottom), plus the pitch-averaged cogs for cushion points. As the
// geometry, the body forces B_r, B_l are the mean over one cog pitch centred on the point (a
// cushion point carries the flank forces its pitch gathers, not the value at one path position;
// docs/decisions.md "Beam level: the body forces over one cog pitch").
#include <string>
#include <vector>

#include "fitlib/belt/load_cycle.hpp"
#include "fitlib/fatigue/life.hpp"

namespace fitlib::fatigue {

struct BeamSection {
  // Geometry below the cord line (the reference cogged section, docs/segment.md, "Mesh").
  double cushion_mm = 0.5;
  double land_depth_mm = 4.1;  // cord line to the gap bottom
  double cog_depth_mm = 2.5;
  double cog_fill = 0.51;      // share of the pitch the cogs fill (§5a: pitch 9, gap 3.5–5.3 mm)
  double pitch_mm = 9.0;       // cog pitch: the path length the body forces are averaged over (0: none)
  // Layer moduli at the drive's temperature and load frequency (MPa) and Poisson's ratio.
  double bottom_modulus_MPa = 10.0;
  double cushion_modulus_MPa = 10.0;
  double poisson = 0.499;
  double manufactured_curvature_1_mm = 0.0;  // K_m, the stress-free (moulded) curvature
  double gap_stress_concentration = 1.0;     // k_t on σ22 at the gap centre line
  // Depths below the cord line of the monitored points (empty: the §5a points, gap bottom and
  // mid-cushion).
  std::vector<double> bottom_depths_mm, cushion_depths_mm;
};

// ε22 of a layer at depth d below the cord line, (1 + ε)(1 − K d)/(1 − K_m d) − 1, with ε = F/c the
// cord strain, K the curvature and K_m the moulded one (the table above; the heat source's stretch).
double layer_stretch(double cord_strain, double K_1_mm, double K_m_1_mm, double depth_mm);

// Project defaults for a drive: the §5a geometry, both layers at E = EI/834 mm⁴ with the
// drive's bending stiffness EI (the bottom card's E22' or the Fritzson law 6.5, as the load
// cycle used; the law at `temperature_C` if the drive has none), and the belt moulded as a ring
// of its own length, K_m = 2π/L (docs/decisions.md "fatigue: where the beam level lives").
BeamSection default_beam_section(const belt::DriveCase& drive, double temperature_C);

// Stress histories of the monitored points over one load cycle (time = s/V).
// InputError for a non-positive belt speed, depths outside their layer, moduli ≤ 0,
// ν outside (−1, 0.5) or a negative pitch.
std::vector<PointHistory> beam_stress_histories(const belt::LoadCycle& cycle,
                                                const belt::DriveCase& drive,
                                                const BeamSection& section);

// Cycle time, cycles per hour, the pulleys' shares and the cord force of a load cycle
// (InputError for a standing belt).
LifeConditions cycle_conditions(const belt::LoadCycle& cycle, const belt::DriveCase& drive,
                                double temperature_C);

// The whole beam level: load cycle + section + fatigue card → life report.
LifeReport beam_life(const belt::LoadCycle& cycle, const belt::DriveCase& drive,
                     const BeamSection& section, const FatigueCard& card, double temperature_C,
                     const PeakOptions& peaks = {});

}  // namespace fitlib::fatigue
