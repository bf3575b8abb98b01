#pragma once
// Staged fitting (docs/fitting.md, "Staged schedules": sub-optimisations with some variables locked, then a
// final global one). A schedule is a list of stages; each frees a selection of parameters, locks
// others, and runs one backend. Parameters fixed by FitOptions::fixed stay fixed throughout.
//
// Schedule file (JSON, or TOML with the same keys; docs/fitting.md has an example):
//   {"stages": [
//     {"name": "global start", "free": ["*"], "backend": "nlopt", "multistart": 8},
//     {"name": "viscous", "free": ["group:viscous", "tau_*"], "backend": "ceres"},
//     {"name": "finish", "free": ["*"], "lock": ["C2"], "backend": "ceres"}]}
// Selectors: "*" (all), "group:<g>" (ParameterSpec::group), "<prefix>*" (names starting with
// prefix), or an exact parameter name.
#include <string>
#include <vector>

#include "fitlib/core/parameter.hpp"

namespace fitlib::fit {

struct Stage {
  std::string name;
  std::vector<std::string> free = {"*"};
  std::vector<std::string> lock;
  std::string backend = "ceres";  // nnls | ceres | nlopt
  int multistart = 0;             // nlopt starts; 0 = FitOptions::multistart
  int max_iterations = 0;         // 0 = FitOptions::max_iterations
};

struct Schedule {
  std::vector<Stage> stages;
};

// Reads a schedule (.toml by extension, JSON otherwise); InputError names file and key.
Schedule load_schedule(const std::string& path);
Schedule parse_schedule_json(const std::string& text, const std::string& source = "schedule");

// Default: a global NLopt multistart over all free parameters, then a Ceres finish.
Schedule default_schedule();

// Indices (model order) selected by `selectors`; InputError (key `key`) for one that matches
// nothing.
std::vector<int> select_parameters(const std::vector<core::ParameterSpec>& specs,
                                   const std::vector<std::string>& selectors,
                                   const std::string& key);

}  // namespace fitlib::fit
