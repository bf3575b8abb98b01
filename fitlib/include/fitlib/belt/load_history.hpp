#pragma once
// What a belt point goes through in one load cycle, as the segment solver reads it: path
// position s, time t, belt force F, longitudinal strain ε = F/c (A.3), curvature K, side pressure
// p, sliding angle γ, temperature and the friction used, linearly interpolated between the load cycle's samples and
// periodic over the belt length (and over the cycle time).
#include <vector>

#include "fitlib/belt/load_cycle.hpp"

namespace fitlib::belt {

struct LoadState {
  double s_mm = 0.0, t_s = 0.0;
  double F_N = 0.0;
  double strain = 0.0;       // F / c
  double K_1_mm = 0.0;
  double p_MPa = 0.0;
  double gamma_rad = 0.0;
  double temperature_C = 0.0;
  double friction_used = 0.0;  // μ × the friction utilisation (the driver exit's ramp; 0 off the pulleys)
  double slide_mm_s = 0.0;     // the flank's sliding speed on the pulley (LoadSample::slide_mm_s)
};

class LoadHistory {
 public:
  // From a computed load cycle; `temperature_C` is the belt's (uniform) temperature.
  // InputError when the cycle has no samples or a non-positive length.
  LoadHistory(const LoadCycle& cycle, const BeltSection& belt, double temperature_C);

  double length_mm() const { return length_mm_; }
  double period_s() const { return period_s_; }  // 0 when the belt speed is 0
  const std::vector<LoadState>& samples() const { return samples_; }

  // At path position s (any real number: taken modulo the length). At a jump (two samples at
  // the same s) the value after the jump.
  LoadState at_position(double s_mm) const;
  // At time t (modulo the cycle time); core::UsageError when the belt does not move.
  LoadState at_time(double t_s) const;
  // The same history with its path origin at s (its time origin where the belt passes s): the
  // result's at_position(x) is this one's at_position(x + s), its samples the same, rotated.
  LoadHistory shifted(double s_mm) const;

 private:
  std::vector<LoadState> samples_;
  double length_mm_ = 0.0, period_s_ = 0.0;
};

}  // namespace fitlib::belt
