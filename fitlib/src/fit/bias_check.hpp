#pragma once
// Bias check of the quality verdict (docs/fitting.md "Quality verdict", issue 35): residuals of
// one modulus that keep one sign (too few sign runs over frequency, Wald–Wolfowitz) or whose
// mean signed error lies many standard errors from 0. A fit can be within the size thresholds
// and still be systematically low: the README tour's G″ was 8–18 % low at all 7 points.
#include <optional>
#include <string>
#include <vector>

namespace fitlib::fit::detail {

struct SignedError {
  double frequency_Hz = 0.0;
  double error = 0.0;  // (model − data) / data
};

// A bias is reported when it is also large enough to matter: the mean signed error (or the rms
// of a run-ordered residual) above this share of the modulus's mean-error threshold.
constexpr double kBiasFloorShare = 0.2;
constexpr double kRunsFloorFactor = 2.5;  // the runs test's floor: 2.5 × the mean test's (half the threshold)
constexpr double kBiasZ = 4.0;  // |t| of the mean, or −z of the runs test, that is a bias

struct GroupBias {
  std::string group;
  int count = 0, runs = 0;
  double expected_runs = 0.0, runs_z = 0.0;
  double mean = 0.0, standard_error = 0.0;
};

// The bias of one group's residuals (sorted by frequency inside), or nothing. Needs ≥ 5 residuals
// for the mean test and ≥ 10 for the runs test; `floor` is the smallest mean (or rms) counted.
std::optional<GroupBias> group_bias(std::vector<SignedError> errors, double floor);

// One warning naming the modulus, its biased groups and their figures.
std::string bias_warning(const std::string& modulus, const std::vector<GroupBias>& groups);

}  // namespace fitlib::fit::detail
