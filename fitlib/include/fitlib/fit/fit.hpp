#pragma once
// Fitting a model to a dynamic-test table: one problem description, several backends.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fitlib/data/table.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::fit {

enum class Backend { automatic, nnls, ceres, nlopt, staged };
// log10 of storage/loss (default), errors relative to each modulus, or errors of E′ and E″
// relative to the row's |E*| (how FE vendors weigh a complex-modulus fit).
enum class ResidualKind { log10, relative, complex };
// The local descent of the automatic and ceres backends (and of the re-polishes after term merges):
// Ceres's Levenberg–Marquardt (dense QR of the augmented Jacobian per step), or fitlib's own on the
// normal equations JᵀJ (fit/levenberg_marquardt.cpp), cheaper per step on small dense problems.
enum class LocalDescent { ceres, normal_equations };

Backend parse_backend(const std::string& text);      // "auto|nnls|ceres|nlopt|staged"
const char* to_string(Backend backend);

struct FitOptions {
  Backend backend = Backend::automatic;
  ResidualKind residual = ResidualKind::log10;
  double storage_weight = 1.0;  // relative weights of the E′, E″ and mean-modulus residuals
  double loss_weight = 1.0;
  double mean_weight = 1.0;     // used only for rows that carry a mean modulus
  std::uint64_t seed = 1;
  int multistart = 16;          // NLopt global starts
  double tolerance = 1e-10;     // relative function tolerance
  int max_iterations = 500;
  std::vector<std::string> fixed;  // parameter names held at their start value
  bool progress = false;           // progress on stderr for multistart runs
  // NNLS backend: after the linear solve, polish the positive moduli on the exact objective
  // (log10 or relative) in log space with Ceres. Off = the pure linear solve.
  bool polish = true;
  // nnls backend: solve the linear parameters first (off: start from the given values, e.g. a
  // regularised spectrum, and only polish).
  bool linear_start = true;
  // automatic backend: always run the NLopt multistart before Ceres (non-convex models).
  bool global = false;
  // staged backend: schedule file (.json or .toml, see fit/staged.hpp); empty = default schedule.
  std::string schedule_path;
  // Admissible terms of series models (docs/fitting.md "Admissible terms"): relaxation times in
  // [10^-m / ω_max, 10^m / ω_min] of the reduced data (m = tau_margin_decades); every term's
  // modulus ≤ modulus_ceiling × the largest measured storage; the relaxed modulus ≥
  // relaxed_floor × the lowest measured storage (0: the user lets it collapse).
  double tau_margin_decades = 1.0;
  double modulus_ceiling = 10.0;
  double relaxed_floor = 0.1;
  // Wall times in the result's messages (staged fits) only when asked: same input, same bytes.
  bool record_timing = false;
  // The smooth spectrum's penalty weight λ (> 0: set by fit_spectrum): the confidence band is then
  // the posterior of the series moduli under the spectrum's smoothness prior, not the bare
  // least-squares covariance (docs/decisions.md "Confidence band under the smoothness prior").
  double band_smoothness = 0.0;
  // false: the values, metrics and verdict only, without covariance, intervals, band or the merges
  // of unidentifiable terms (the term economy's trial fits, whose figures alone are compared).
  bool uncertainty = true;
  // Which local descent the automatic and ceres backends run (fit_fixed_terms's polish: normal
  // equations; docs/fitting.md "Fixed term counts").
  LocalDescent descent = LocalDescent::ceres;
};

// The window a fit's series terms were held in (card "fit.admissible"; export checks it).
struct AdmissibleWindow {
  bool applies = false;  // false: the model has no series terms (or an unknown shift law)
  double tau_min_s = 0.0, tau_max_s = 0.0;
  double modulus_max_MPa = 0.0;  // ceiling of each term's modulus (0: none, e.g. compliances)
  double relaxed_min_MPa = 0.0;  // floor of the relaxed modulus (0: none)
  double glassy_modulus_max_MPa = 0.0;  // ceiling of a compliance series' 1/J_g (0: none)
};

// Relative errors |model − data| / data of one modulus over one group of rows.
struct ErrorFigures {
  std::string group;      // "all", "T=23 degC", "mode shear", ...
  std::string modulus;    // "storage" | "loss" | "mean"
  int count = 0;
  double mean_rel_error = 0.0, max_rel_error = 0.0;
  double max_at_frequency_Hz = 0.0;  // where the largest error sits
};

// Quality verdict after every fit (docs/fitting.md "Quality verdict").
struct QualityVerdict {
  std::vector<ErrorFigures> figures;  // per modulus for all rows, then per temperature/mode group
  std::vector<std::string> warnings;  // one per figure past its threshold, and data warnings
  // Where the data are not Kramers–Kronig consistent: runs of rows in frequency order where the
  // storage is fitted and the loss it implies is off by > 1.5× (docs/decisions.md "Kramers–Kronig
  // inconsistent ranges"), each (lo, hi) in Hz; empty: nowhere found.
  std::vector<std::pair<double, double>> kramers_kronig_ranges_Hz;
  bool acceptable() const { return warnings.empty(); }
};

// The 95 % confidence band of the fitted curve at one frequency (docs/fitting.md "Confidence
// band"): E′, E″ and tan δ with their intervals from the covariance of the free parameters
// (delta method on the logarithms, Student's t with the fit's degrees of freedom).
struct BandPoint {
  double frequency_Hz = 0.0;
  double storage = 0.0, storage_low = 0.0, storage_high = 0.0;
  double loss = 0.0, loss_low = 0.0, loss_high = 0.0;
  double tan_delta = 0.0, tan_delta_low = 0.0, tan_delta_high = 0.0;
};
struct ConfidenceBand {
  model::TestCondition condition;  // mode and temperature of the band (the first row's)
  std::vector<BandPoint> points;   // 20 per decade over the data's frequencies; empty: no covariance
};

struct ParameterResult {
  std::string name, unit;
  double value = 0.0;
  bool fixed = false;
  std::optional<double> std_error;  // empty when not estimable; see reason
  std::string reason;
  bool at_bound = false;  // free and ended on one of its bounds (no interval; the verdict warns)
  std::optional<double> ci95_low, ci95_high;
};

struct FitMetrics {
  int n_points = 0;            // rows used
  int n_residuals = 0;
  int n_free = 0;              // free parameters
  double cost = 0.0;           // ½ Σ weighted residual²
  double rms_log10_storage = 0.0, rms_log10_loss = 0.0;
  double mean_rel_error = 0.0, max_rel_error = 0.0;
  double aic = 0.0, bic = 0.0;
  double wall_time_s = 0.0;
  bool converged = false;
  double condition_number = 0.0;
  int rank = 0;                // numerical rank of the Jacobian at the solution
  int iterations = 0;
  int n_active = 0;            // parameters with a usable standard error
};

// Which parameters the data cannot pin down (SVD of the column-scaled Jacobian at the solution).
struct Identifiability {
  double condition_number = 0.0;  // of the column-scaled Jacobian (free parameters)
  int rank = 0;
  // One entry per null-space direction: the parameter names dominating it.
  std::vector<std::vector<std::string>> null_space;
  // Every free parameter the data cannot determine: no effect on the residuals, or more than
  // 1 % of its weight in the null space (a superset of the names in null_space).
  std::vector<std::string> not_identifiable;
  // Pairs of parameters whose correlation exceeds 0.99 in magnitude.
  struct Pair {
    std::string a, b;
    double correlation;
  };
  std::vector<Pair> correlated;
};

// The covariance of the parameters with a standard error (docs/formats.md §3 fit.covariance), in
// the coordinates the fit moved them in: ln p where `log` (positive parameters), p otherwise. The
// card carries it so a life can propagate it (docs/thermal.md §7, [life] uncertainty = "cards").
struct ParameterCovariance {
  std::vector<int> index;                  // model parameter indices, ascending
  std::vector<bool> log;                   // per entry: the coordinate is ln p
  std::vector<std::vector<double>> matrix; // index.size() squared
};

struct FitResult {
  model::ModelPtr model;
  std::vector<double> values;               // in model order
  std::vector<ParameterResult> parameters;  // in model order
  FitMetrics metrics;
  std::string backend_used;
  std::vector<std::string> messages;        // warnings, notes (e.g. rank deficiency)
  Identifiability identifiability;
  std::string objective;                    // e.g. "sum of squared log10 errors, w(E')=10"
  AdmissibleWindow admissible;
  QualityVerdict quality;
  ConfidenceBand band;
  ParameterCovariance covariance;           // empty without standard errors
};

// Fits `model` to `table`. `start` overrides the model's initial_parameters(summary).
FitResult fit(const model::ModelPtr& model, const data::DynamicTestTable& table,
              const FitOptions& options, const std::vector<double>* start = nullptr);

// Summary of the data a model uses to place its start.
model::DataSummary summarize(const data::DynamicTestTable& table);

ResidualKind parse_residual_kind(const std::string& text);  // "log10|relative|complex"
const char* to_string(ResidualKind kind);

}  // namespace fitlib::fit
