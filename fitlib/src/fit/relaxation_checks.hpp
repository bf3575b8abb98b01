#pragma once
// Private to the fit module: what relaxation fits share with frequency fits — the admissible
// window (docs/fitting.md "Admissible terms", with t read as 1/ω) and the quality verdict
// (docs/fitting.md "Quality verdict", the storage thresholds for M(t)).
#include <vector>

#include "fitlib/data/relaxation.hpp"
#include "fitlib/fit/fit.hpp"

namespace fitlib::fit::detail {

// Time and modulus range of the table (ω ∈ [1/t_max, 1/t_min]: a τ is seen at t ≈ τ).
model::DataSummary summarize_relaxation(const data::RelaxationTable& table);

// The window of a series model on relaxation data: τ ∈ [t_min / 10^m, 10^m t_max], each
// modulus ≤ modulus_ceiling × the largest M_i, the relaxed modulus ≥ relaxed_floor × the
// smallest M_i. applies = false without series terms or with a temperature law (the times would
// have to be reduced by the law first).
AdmissibleWindow relaxation_window(const model::Model& model, const data::RelaxationTable& table,
                                   const FitOptions& options);

// Lower and upper bound of parameter i under the window (intersected with its spec's bounds).
std::pair<double, double> window_bounds(const model::Model& model, const AdmissibleWindow& window, int i);

// Mean and max relative error of M(t) over all rows ("relaxation" figure; its frequency is
// 1/(2π t) of the worst row), with a warning past the storage thresholds.
QualityVerdict relaxation_verdict(const model::Model& model, const std::vector<double>& p,
                                  const data::RelaxationTable& table);

}  // namespace fitlib::fit::detail
