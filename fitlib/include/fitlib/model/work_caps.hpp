#pragma once
// Work caps of a material point's histories (README "Work caps", docs/reliability.md §4), shared by
// fitcli material-point and the Python module's drive, drive_test and fritzson_thesis_case. A
// history is capped by what it costs, estimated before it runs from the point's state size: CPU
// seconds on the 2-core reference machine (the cost model below, measured there) and rows of
// output (each row one time step: about 70 bytes of CSV, 13 doubles in memory).
#include <cstddef>
#include <string>

#include "fitlib/model/test_condition.hpp"

namespace fitlib::model {

constexpr double kMaxPointSteps = 1e6;    // rows of one history (about 70 MB of CSV)
constexpr double kMaxPointSeconds = 10.0;  // estimated CPU seconds of one history

// CPU cost of one time step of model::drive with fitcli's CSV row, measured with `fitcli
// material-point` (release build, load 11 on the 2 cores, 2·10⁵ steps; docs/reliability.md §4):
// a row and the driver kStepCostS, and per point update kUpdateCostS + kStateValueCostS per double
// of the point's state. A program with stress-controlled (traction-free) components takes about
// kStressControlledUpdates updates a step (the Newton correction of the free components).
constexpr double kStepCostS = 2.25e-6;
constexpr double kUpdateCostS = 2.55e-6;
constexpr double kStateValueCostS = 4.3e-9;
constexpr double kStressControlledUpdates = 2.0;

// The estimate of one history: `steps` time steps of a point with `state_size` doubles of state.
struct PointWork {
  double steps = 0.0;
  double updates_per_step = 1.0;
  double seconds = 0.0;
  std::size_t state_size = 0;
};
PointWork point_work(std::size_t state_size, double steps, bool stress_controlled);
// The same for a test of `mode` (model::test_program): a uniaxial test leaves the lateral stresses
// free (stress-controlled), shear and bulk tests impose every strain.
PointWork point_work(std::size_t state_size, double steps, TestMode mode);

// core::InputError naming `key` (the option or argument that sets the length, e.g. "--cycles x
// --steps-per-cycle") with the estimate, when the history is above kMaxPointSteps rows or
// kMaxPointSeconds; `what` names the point in the message ("prony (shear card)").
void check_point_work(const PointWork& work, const std::string& what, const std::string& key);

}  // namespace fitlib::model
