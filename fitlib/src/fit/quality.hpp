#pragma once
// Quality verdict of a finished fit (docs/fitting.md "Quality verdict"), private to the module.
#include <vector>

#include "fitlib/fit/problem.hpp"

namespace fitlib::fit::detail {

// Temperatures closer than this are one isotherm (MasterCurveOptions::same_temperature_C).
constexpr double kSameTemperature_C = 0.5;

// Thresholds past which a fit warns: mean and max relative error per modulus.
struct QualityThresholds {
  double storage_mean = 0.05, storage_max = 0.15;  // also used for the mean modulus
  double loss_mean = 0.15, loss_max = 0.40;
};

// Relative errors per modulus over all rows and per temperature / mode group, warnings past the
// thresholds, and (series models) the frequency range where the data are not Kramers–Kronig
// consistent: storage fitted within its threshold, the loss it implies far off.
QualityVerdict quality_verdict(const Problem& problem, const std::vector<double>& p,
                               const QualityThresholds& thresholds = {});

// As many free parameters as residuals or more (the fit's final count, FitMetrics): the card passes
// through the points whatever it is, so its small errors vouch for nothing; adds that warning to
// `quality` (docs/decisions.md "Quality: no residual degrees of freedom").
void degrees_of_freedom_warning(const FitMetrics& metrics, QualityVerdict& quality);

// Throws InputError when the rows span several temperatures and the model has no temperature
// law: one curve would be fitted to several materials' states (the merged-isotherm trap).
void check_single_temperature(const model::Model& model, const data::DynamicTestTable& table);

}  // namespace fitlib::fit::detail
