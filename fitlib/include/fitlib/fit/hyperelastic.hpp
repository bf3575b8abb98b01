#pragma once
// Hyperelastic fits (docs/hyperelastic.md §"Fitting"): quasi-static rows → the parameters of a
// hyperelastic model by Ceres (relative or absolute nominal-stress residuals, per-mode weights),
// multistart over the non-linear parameters with the linear ones solved exactly at each start,
// standard errors from the Jacobian, a quality verdict per mode and the Drucker stability check.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fitlib/data/quasi_static.hpp"
#include "fitlib/model/hyperelastic.hpp"

namespace fitlib::fit {

enum class StressResidual { relative, absolute };
StressResidual parse_stress_residual(const std::string& text);  // "relative" | "absolute"
std::string to_string(StressResidual residual);

struct HyperelasticFitOptions {
  StressResidual residual = StressResidual::relative;
  std::map<model::DeformationMode, double> mode_weights;  // missing: 1
  int multistart = 0;  // starts; 0: 1 without non-linear parameters, else 20 per non-linear parameter
  std::uint64_t seed = 1;
  int max_iterations = 500;
  // Drucker stability is checked from stretch 1 to these in uniaxial, equibiaxial and planar
  // tension and compression (the range of the reference fits, datasets/materials/README.md).
  double stability_min_stretch = 0.1, stability_max_stretch = 10.0;
  // Quality verdict thresholds, relative errors per mode.
  double rms_threshold = 0.10, bias_threshold = 0.05;
};

// Errors of a law against rows of one mode (relative: P_model/P_data − 1).
struct ModeFigure {
  model::DeformationMode mode = model::DeformationMode::uniaxial;
  int count = 0;
  double rms_rel_error = 0.0, max_rel_error = 0.0, max_at = 0.0;  // max of |error|, at this abscissa
  double mean_rel_error = 0.0;  // signed: the bias
  double abscissa_min = 0.0, abscissa_max = 0.0;
};

// Drucker stability along one mode and direction: the first unstable stretch (0: stable up to
// the checked limit) and whether it lies within the stretches the data of that mode reached.
struct StabilityFinding {
  model::DeformationMode mode = model::DeformationMode::uniaxial;
  bool tension = true;
  double checked_to = 10.0;
  double unstable_from = 0.0;
  bool inside_data = false;
  bool locking = false;  // the law ends there (Gent's locking stretch) rather than turning unstable
};

struct HyperelasticFitResult {
  model::ModelPtr model;
  std::vector<double> values;
  std::vector<std::optional<double>> std_error;  // empty where not identifiable
  std::vector<std::string> std_error_reason;
  std::vector<std::optional<double>> ci95_low, ci95_high;
  double cost = 0.0;  // ½ Σ r²
  int n_points = 0, n_free = 0, starts = 0, iterations = 0;
  bool converged = false;
  std::vector<ModeFigure> figures;
  std::vector<StabilityFinding> stability;
  std::vector<std::string> warnings;  // quality verdict and stability beyond the data
  std::vector<std::string> messages;  // dropped rows, chosen start
  bool acceptable() const { return warnings.empty(); }
};

// Throws core::InputError for rows the law cannot take (volumetric rows for an incompressible law,
// a compressible law without them), core::NumericalError when no start converges or the law is
// Drucker-unstable within the data (naming mode and stretch).
HyperelasticFitResult fit_hyperelastic(const data::QuasiStaticTable& table, model::ModelPtr model,
                                       const HyperelasticFitOptions& options = {});

// The figures of a law with parameters p on rows it was or was not fitted to (a prediction).
std::vector<ModeFigure> hyperelastic_figures(const model::HyperelasticLaw& law, const double* p,
                                             const data::QuasiStaticTable& table);

// Drucker findings of p over the options' stretch range; inside_data against `table`'s rows.
std::vector<StabilityFinding> drucker_findings(const model::HyperelasticLaw& law, const double* p,
                                               const data::QuasiStaticTable& table,
                                               const HyperelasticFitOptions& options);
// One line for a finding ("unstable in equibiaxial tension from stretch 1.35 (Drucker)"), "" when stable.
std::string describe(const StabilityFinding& finding);

}  // namespace fitlib::fit
