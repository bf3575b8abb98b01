#pragma once
// The test cases of thesis Report II §7.2 (docs/fritzson.md §7) at one
// material point: four cyclic cases (mean deformation −1 × amplitude, 10 cycles, starting at zero)
// and the interrupted ramp, with stress–strain loops as CSV.
#include <array>
#include <string>
#include <vector>

#include "fitlib/model/fritzson_point.hpp"

namespace fitlib::model::fritzson {

struct ThesisCase {
  std::string id;                  // "7.1" … "7.5"
  TestMode mode;                   // uniaxial or shear
  std::string orientation;         // "22", "33", "21", "23"
  double displacement_amplitude;   // relative displacement u/L (cyclic cases) or final u/L (ramp)
  double frequency_Hz;             // cyclic cases; 0 for the ramp
  double temperature_C;
  double ramp_rate_per_s = 0.0;    // 7.5: log-strain rate of the ramp
  double hold_s = 0.0;             // 7.5: hold after the ramp (decision, docs/decisions.md)
};

// The thesis integrator (exponential scheme) of a fritzson or fritzson-iso model with
// parameters p; core::UsageError for any other model.
MaterialPoint thesis_point(const Model& model, const std::vector<double>& p);

// The five cases of the thesis table; throws UsageError for an unknown id.
const std::vector<ThesisCase>& thesis_cases();
const ThesisCase& thesis_case(const std::string& id);

struct CaseLoops {
  std::vector<double> time_s;
  std::vector<double> displacement;     // u/L
  std::vector<double> strain;           // uniaxial: ln(1 + u/L); shear: γ = u/L (docs/fritzson.md §7)
  std::vector<double> stress_MPa;       // uniaxial: Kirchhoff σ along the axis; shear: τ
  std::vector<double> nominal_MPa;      // force / undeformed area (uniaxial τ/λ; shear τ)
  std::vector<std::array<double, 3>> driver_amplitude;  // damage e^a of I, A1, A2
};

// Runs a case with the logarithmic (total) strain variant; `steps_per_cycle` for the cyclic
// cases, the ramp uses the same count over its rise and 1 ms steps in the hold.
CaseLoops run_thesis_case(const MaterialPoint& point, const ThesisCase& c,
                          int steps_per_cycle = 200);
// The work cap of run_thesis_case (model/work_caps.hpp), before it runs: its time steps (rows) and
// the cost of the card's point; core::InputError naming `key` (the option or argument that sets
// steps_per_cycle) when above the cap.
void check_thesis_case_work(const Model& model, const std::vector<double>& p, const ThesisCase& c,
                            int steps_per_cycle, const std::string& key);

// time_s,displacement,strain,stress_MPa,nominal_stress_MPa,damage_driver_I,_A1,_A2 (+ comments).
std::string case_loops_csv(const ThesisCase& c, const CaseLoops& loops);

}  // namespace fitlib::model::fritzson
