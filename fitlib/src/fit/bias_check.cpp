#include "bias_check.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fitlib::fit::detail {
namespace {

// Wald–Wolfowitz: runs of one sign among n₊ positive and n₋ negative residuals have mean
// 2n₊n₋/n + 1 and variance (μ − 1)(μ − 2)/(n − 1) under independence.
void runs_test(const std::vector<SignedError>& e, GroupBias& b) {
  int plus = 0, minus = 0;
  int previous = 0;
  for (const auto& x : e) {
    const int sign = x.error > 0.0 ? 1 : x.error < 0.0 ? -1 : 0;
    if (sign == 0) continue;
    (sign > 0 ? plus : minus)++;
    if (sign != previous) ++b.runs;
    previous = sign;
  }
  const double n = plus + minus;
  if (n < 2.0) return;
  b.expected_runs = 2.0 * plus * minus / n + 1.0;
  const double variance = (b.expected_runs - 1.0) * (b.expected_runs - 2.0) / (n - 1.0);
  b.runs_z = variance > 0.0 ? (b.runs - b.expected_runs) / std::sqrt(variance) : 0.0;
}

std::string percent(double x) {
  std::ostringstream s;
  s.precision(3);
  s << 100.0 * x << " %";
  return s.str();
}

}  // namespace

std::optional<GroupBias> group_bias(std::vector<SignedError> errors, double floor) {
  const int n = static_cast<int>(errors.size());
  if (n < 5) return std::nullopt;
  std::stable_sort(errors.begin(), errors.end(),
                   [](const SignedError& a, const SignedError& b) { return a.frequency_Hz < b.frequency_Hz; });
  GroupBias b;
  b.count = n;
  double sum = 0.0, squares = 0.0;
  for (const auto& x : errors) sum += x.error, squares += x.error * x.error;
  b.mean = sum / n;
  const double variance = std::max(squares / n - b.mean * b.mean, 0.0) * n / (n - 1.0);
  b.standard_error = std::sqrt(variance / n);
  const double rms = std::sqrt(squares / n);
  runs_test(errors, b);
  // All residuals of one sign is the extreme of both tests (its standard error may be small or not).
  const bool mean_biased = std::abs(b.mean) >= floor && std::abs(b.mean) >= kBiasZ * b.standard_error;
  // Correlated residuals are common where a fit is good (a master curve's isotherm segments): the
  // runs test counts only residuals whose rms is half the modulus's mean-error threshold.
  const bool runs_biased = n >= 10 && rms >= kRunsFloorFactor * floor && b.runs_z <= -kBiasZ;
  if (!mean_biased && !runs_biased) return std::nullopt;
  return b;
}

std::string bias_warning(const std::string& modulus, const std::vector<GroupBias>& groups) {
  std::ostringstream s;
  s << "fit is biased on the " << modulus << " modulus (residuals keep one sign where the data do not): ";
  const std::size_t shown = std::min<std::size_t>(groups.size(), 4);
  for (std::size_t k = 0; k < shown; ++k) {
    const GroupBias& b = groups[k];
    s << (k ? "; " : "") << b.group << ": mean signed error " << percent(b.mean) << " (standard error "
      << percent(b.standard_error) << "), " << b.runs << " sign runs over " << b.count << " points (" << b.expected_runs
      << " expected)";
  }
  if (groups.size() > shown) s << "; and " << groups.size() - shown << " more group(s)";
  return s.str();
}

}  // namespace fitlib::fit::detail
