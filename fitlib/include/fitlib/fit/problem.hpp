#pragma once
// The one problem description every backend works on: residuals of a model against a table,
// the free parameters and their transforms (log for positive scales) and bounds.
//
// Coordinates: `natural` = all model parameters in the model's units (MPa, s, ...);
// `x` = the free parameters in fitted coordinates (ln p for log-transformed ones, p otherwise).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fitlib/data/table.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::fit {

// One scalar residual: a modulus of one row.
struct ResidualEntry {
  int row = 0;
  int component = 0;      // 0 storage, 1 loss, 2 mean modulus
  double data = 0.0;      // measured value, MPa
  double sqrt_weight = 1.0;
  // Below the loss floor (tan δ < 1e-6, including a zero loss) the log of the data does not
  // exist: the residual is then absolute, (model − data) / scale, with scale = E′·ln 10 for
  // log10 residuals (so it reads as a log10 error of E′ + E″) or E′ for relative ones.
  bool absolute = false;
  double scale = 1.0;
};

class Problem {
 public:
  // Tan δ below which a loss modulus is treated as zero (absolute residual, see ResidualEntry).
  static constexpr double kLossFloor = 1e-6;

  Problem(model::ModelPtr model, const data::DynamicTestTable& table, FitOptions options,
          std::vector<double> natural_start);

  const model::Model& model() const { return *model_; }
  const model::ModelPtr& model_ptr() const { return model_; }
  const data::DynamicTestTable& table() const { return *table_; }
  const FitOptions& options() const { return options_; }
  const std::vector<core::ParameterSpec>& specs() const { return model_->parameters(); }
  const std::vector<ResidualEntry>& entries() const { return entries_; }

  int num_parameters() const { return static_cast<int>(specs().size()); }
  int num_residuals() const { return static_cast<int>(entries_.size()); }
  int num_free() const { return static_cast<int>(free_.size()); }

  // Indices (model order) of the free parameters; default: all but FitOptions::fixed.
  const std::vector<int>& free() const { return free_; }
  void set_free(std::vector<int> free);
  // Parameters fixed by the user (FitOptions::fixed); stages never free them.
  const std::vector<bool>& user_fixed() const { return user_fixed_; }

  // Current values of all parameters, natural units.
  std::vector<double>& natural() { return natural_; }
  const std::vector<double>& natural() const { return natural_; }

  // Bounds of parameter i in natural units (the model's, tightened by the fitter, e.g. WLF C2).
  double lower(int i) const { return lower_[i]; }
  double upper(int i) const { return upper_[i]; }
  bool is_log(int i) const;
  // Narrows the bounds of parameter i (never widens the model's own) and moves its current
  // value inside them; returns true when the value moved.
  bool restrict_bounds(int i, double lower, double upper);

  // Fitted coordinates of the free parameters for the natural vector `natural`.
  Eigen::VectorXd to_x(const std::vector<double>& natural) const;
  // Writes the free parameters of `x` into `natural` (other entries untouched).
  void from_x(const double* x, std::vector<double>& natural) const;
  // Bounds of free parameter k in fitted coordinates (±inf when none).
  double lower_x(int k) const;
  double upper_x(int k) const;

  // Residuals at `natural`, and if `jacobian` is non-null the row-major (residuals × free)
  // derivatives with respect to x. Returns false if anything is not finite.
  bool evaluate(const std::vector<double>& natural, double* residuals, double* jacobian) const;
  // Why evaluation fails at `natural`: the first row whose moduli are refused or not finite.
  std::string diagnose(const std::vector<double>& natural) const;
  // ½ Σ r²; +inf when evaluation fails.
  double cost(const std::vector<double>& natural) const;

  // Data fit measures at `natural` (independent of weights): rms log10 errors and relative errors.
  void measure(const std::vector<double>& natural, FitMetrics& metrics) const;

  // Notes gathered while setting up (bounds tightened, starts clamped).
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  bool evaluate_unchecked(const std::vector<double>& natural, double* residuals,
                          double* jacobian) const;

  void tighten_temperature_bounds();
  void clamp_start();

  model::ModelPtr model_;
  const data::DynamicTestTable* table_;
  FitOptions options_;
  std::vector<ResidualEntry> entries_;
  // Rows with the same test condition (repeat specimens) share one model evaluation.
  std::vector<int> condition_of_row_;  // index into distinct_rows_
  std::vector<int> distinct_rows_;     // first row of each distinct condition
  std::vector<int> free_;
  std::vector<bool> user_fixed_;
  std::vector<double> natural_, lower_, upper_;
  std::vector<std::string> notes_;
};

// "storage" / "loss" / "mean" for messages.
const char* component_name(int component);

}  // namespace fitlib::fit
