#pragma once
// Specimen constants of a waveform record (formats.md §2) and the force/displacement → stress/
// strain conversion they allow (docs/data.md "Waveform").
#include <limits>
#include <string>
#include <vector>

#include "fitlib/core/test_condition.hpp"

namespace fitlib::data {

// Specimen constants (formats.md §2) and labels for the table row.
struct SpecimenInfo {
  core::TestMode mode = core::TestMode::shear;
  bool has_mode = false;
  double area_mm2 = std::numeric_limits<double>::quiet_NaN();       // loaded area, one specimen
  double thickness_mm = std::numeric_limits<double>::quiet_NaN();   // shear: sheared height h
  double length_mm = std::numeric_limits<double>::quiet_NaN();      // uniaxial: length L
  double volume_mm3 = std::numeric_limits<double>::quiet_NaN();     // bulk: V0
  int n_specimens = 1;  // double-sandwich shear: 2 (τ = F/(n·A))
  double temperature_C = std::numeric_limits<double>::quiet_NaN();
  std::string material, specimen, orientation;
};

// Stress (MPa) and strain from force (N) and displacement (mm):
// shear τ = F/(n·A), γ = u/h; uniaxial σ = F/(n·A), ε = u/L; bulk p = F/A, ε_v = A·u/V0.
// Throws InputError naming the missing or non-positive specimen key.
void stress_strain_from_force(const SpecimenInfo& specimen, const std::vector<double>& force_N,
                              const std::vector<double>& displacement_mm,
                              std::vector<double>& stress_MPa, std::vector<double>& strain);

}  // namespace fitlib::data
