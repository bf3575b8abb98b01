#pragma once
// Fitting a model's relaxation modulus M(t) to relaxation tests (docs/fitting.md, "Relaxation
// data"): residual log10 M(t_i) − log10 M_i, a non-negative linear solve for the modulus weights
// on the model's start grid, then a log-space polish of all free parameters (Ceres). Term counts
// are chosen with the same rules as for frequency data (fit/terms.hpp).
#include <string>

#include <nlohmann/json.hpp>

#include "fitlib/data/relaxation.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/terms.hpp"

namespace fitlib::fit {

// Figures of a model against relaxation data (independent of weights).
struct RelaxationMeasures {
  double rms_log10 = 0.0;      // rms of log10 M(t) − log10 M_i
  double rms_relative = 0.0;   // rms of (M(t) − M_i) / M_i
  double max_relative = 0.0;
  double mean_relative = 0.0;
};
RelaxationMeasures measure_relaxation(const model::Model& model, const std::vector<double>& p,
                                      const data::RelaxationTable& table);

// Fits `model` to `table`. FitResult::metrics: rms_log10_storage holds the rms log10 error of
// M(t) (rms_log10_loss = 0), mean/max_rel_error the relative errors of M(t).
// Uses FitOptions::fixed, tolerance, max_iterations and polish; throws NumericalError on failure.
// `start` (natural values) replaces the model's start and the linear solve.
FitResult fit_relaxation(const model::ModelPtr& model, const data::RelaxationTable& table,
                         const FitOptions& options, const std::vector<double>* start = nullptr);

// N = min…max terms (max 0: one per decade of the time span + 2, at most 40) ranked on their
// linear solves by `terms.rule`, or the smallest N reaching `terms.accuracy_log10` when that is
// fewer; the chosen N polished, its unused terms dropped and adjacent ones merged while the
// polished cost holds (docs/fitting.md "Relaxation data").
TermSelection select_relaxation_terms(const std::string& kind, const nlohmann::json& model_options,
                                      const data::RelaxationTable& table, const FitOptions& options,
                                      const TermOptions& terms);

}  // namespace fitlib::fit
