// The cost model of a material-point history (fitlib/model/work_caps.hpp, docs/reliability.md §4).
#include "fitlib/model/work_caps.hpp"

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib::model {

PointWork point_work(std::size_t state_size, double steps, bool stress_controlled) {
  PointWork w;
  w.steps = steps;
  w.state_size = state_size;
  w.updates_per_step = stress_controlled ? kStressControlledUpdates : 1.0;
  const double update_s = kUpdateCostS + kStateValueCostS * static_cast<double>(state_size);
  w.seconds = steps * (kStepCostS + w.updates_per_step * update_s);
  return w;
}

PointWork point_work(std::size_t state_size, double steps, TestMode mode) {
  return point_work(state_size, steps, mode == TestMode::uniaxial);
}

void check_point_work(const PointWork& w, const std::string& what, const std::string& key) {
  if (w.steps <= kMaxPointSteps && w.seconds <= kMaxPointSeconds) return;
  using core::format_number;
  throw core::InputError(
      format_number(w.steps) + " time steps of " + what + " (" + std::to_string(w.state_size) + " state values, " +
          format_number(w.updates_per_step) + (w.updates_per_step == 1.0 ? " update" : " updates") +
          " per step) would take about " + format_number(w.seconds, 3) +
          " s and write about " + format_number(w.steps * 70e-6, 3) + " MB, above the work cap of " +
          format_number(kMaxPointSeconds) + " s estimated and " + format_number(kMaxPointSteps) +
          " steps (README, work caps); fewer cycles or steps per cycle",
      "", 0, 0, key);
}

}  // namespace fitlib::model
