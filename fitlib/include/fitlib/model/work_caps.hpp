#pragma once
// Work caps of a material point's histories (README "Work caps", docs/reliability.md), shared by
// fitcli material-point and the Python module's drive, drive_test and fritzson_thesis_case: 10^6
// steps of a Prony point take about 5 s and write about 70 MB.
namespace fitlib::model {

constexpr double kMaxPointSteps = 1e6;     // time steps of one history (cycles × steps per cycle)
constexpr int kMaxCaseStepsPerCycle = 10000;  // steps per cycle of a thesis case (7.1–7.5)

}  // namespace fitlib::model
