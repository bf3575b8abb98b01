// Report II §7.2 test cases at one material point.
#include "fitlib/model/fritzson_cases.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/work_caps.hpp"

namespace fitlib::model::fritzson {

const std::vector<ThesisCase>& thesis_cases() {
  static const std::vector<ThesisCase> cases = {
      {"7.1", TestMode::uniaxial, "22", 0.0472, 2.98, 43.3},
      {"7.2", TestMode::uniaxial, "33", 0.00476, 59.5, 36.1},
      {"7.3", TestMode::shear, "21", 0.0156, 34.0, 27.2},
      {"7.4", TestMode::shear, "23", 0.00502, 59.4, 25.0},
      // Ramp at 5.00 1/s to ln 1.1 = 0.0953, then held 1 s (hold time [UNCLEAR]: decision).
      {"7.5", TestMode::uniaxial, "22", 0.1, 0.0, 30.0, 5.0, 1.0}};
  return cases;
}

const ThesisCase& thesis_case(const std::string& id) {
  for (const auto& c : thesis_cases())
    if (c.id == id) return c;
  throw core::UsageError("unknown thesis case '" + id + "' (known: 7.1, 7.2, 7.3, 7.4, 7.5)");
}

CaseLoops run_thesis_case(const MaterialPoint& point, const ThesisCase& c, int steps_per_cycle) {
  if (steps_per_cycle < 4) throw core::UsageError("steps per cycle must be at least 4");
  using core::kPi;
  CaseLoops out;
  StrainHistory h;
  if (c.ramp_rate_per_s > 0.0) {
    const double top = std::log1p(c.displacement_amplitude);
    const double rise = top / c.ramp_rate_per_s;
    for (int k = 0; k <= steps_per_cycle; ++k) {
      h.time_s.push_back(rise * k / steps_per_cycle);
      out.displacement.push_back(std::expm1(top * k / steps_per_cycle));
    }
    const int hold_steps = static_cast<int>(std::ceil(c.hold_s / 1e-3));
    for (int k = 1; k <= hold_steps; ++k) {
      h.time_s.push_back(rise + c.hold_s * k / hold_steps);
      out.displacement.push_back(c.displacement_amplitude);
    }
  } else {
    // Mean deformation = −1 × amplitude, starting from zero: u/L = −a(1 − cos ωt), 10 cycles.
    const int n = 10 * steps_per_cycle;
    for (int k = 0; k <= n; ++k) {
      h.time_s.push_back(double(k) / steps_per_cycle / c.frequency_Hz);
      out.displacement.push_back(c.displacement_amplitude *
                                 (std::cos(2.0 * kPi * k / steps_per_cycle) - 1.0));
    }
  }
  const bool uniaxial = c.mode == TestMode::uniaxial;
  for (double u : out.displacement) h.strain.push_back(uniaxial ? std::log1p(u) : u);
  TestCondition tc;
  tc.mode = c.mode;
  tc.orientation = c.orientation;
  tc.temperature_C = c.temperature_C;
  const DriveResult r = drive_test(point, tc, h);
  out.time_s = h.time_s;
  out.strain = h.strain;
  out.stress_MPa = r.stress;
  out.driver_amplitude = r.driver_amplitude;
  for (size_t k = 0; k < r.stress.size(); ++k)
    out.nominal_MPa.push_back(uniaxial ? r.stress[k] / (1.0 + out.displacement[k]) : r.stress[k]);
  return out;
}

void check_thesis_case_work(const Model& model, const std::vector<double>& p, const ThesisCase& c,
                            int steps_per_cycle, const std::string& key) {
  // The rows of run_thesis_case: the ramp's rise and its 1 ms hold steps, or 10 cycles.
  const double steps = c.ramp_rate_per_s > 0.0 ? steps_per_cycle + 1.0 + std::ceil(c.hold_s / 1e-3)
                                               : 10.0 * steps_per_cycle + 1.0;
  const std::size_t state = make_material_point(model, p)->state_size();  // the thesis point's, as the contract's
  check_point_work(point_work(state, steps, c.mode), "case " + c.id + " of a " + model.kind() + " card", key);
}

std::string case_loops_csv(const ThesisCase& c, const CaseLoops& loops) {
  std::ostringstream out;
  out << "# Report II case " << c.id << ": " << to_string(c.mode) << " " << c.orientation
      << ", relative displacement " << c.displacement_amplitude << ", "
      << (c.ramp_rate_per_s > 0 ? "ramp" : "cyclic") << ", " << c.temperature_C << " C\n"
      << "time_s,displacement,strain,stress_MPa,nominal_stress_MPa,damage_driver_I,"
         "damage_driver_A1,damage_driver_A2\n";
  using core::format_number;
  for (size_t k = 0; k < loops.time_s.size(); ++k) {
    for (double v : {loops.time_s[k], loops.displacement[k], loops.strain[k], loops.stress_MPa[k],
                     loops.nominal_MPa[k]})
      out << format_number(v, 9) << ',';
    const auto& d = loops.driver_amplitude[k];
    out << format_number(d[0], 6) << ',' << format_number(d[1], 6) << ',' << format_number(d[2], 6) << '\n';
  }
  return out.str();
}

}  // namespace fitlib::model::fritzson
