#pragma once
// The arguments of a benchmark mode that times this build's fitcli against a baseline binary
// (`bench_life cost`, `bench_prony process`): [BASELINE_FITCLI] [runs=N], after the mode's name.
#include <algorithm>
#include <cstdlib>
#include <string>

struct BaselineArgs {
  std::string baseline;  // empty: this build alone
  int runs = 1;
};

// argv[2…]: `runs=N` (at least 1), anything else the baseline binary's path.
inline BaselineArgs baseline_args(int argc, char** argv, int default_runs) {
  BaselineArgs out;
  out.runs = default_runs;
  for (int k = 2; k < argc; ++k) {
    const std::string a = argv[k];
    if (a.rfind("runs=", 0) == 0) out.runs = std::max(1, std::atoi(a.c_str() + 5));
    else out.baseline = a;
  }
  return out;
}
