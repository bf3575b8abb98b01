#include "fitlib/fit/fixed_terms.hpp"

#include <cmath>
#include <string>

#include "fitlib/core/format.hpp"
#include "fitlib/fit/spectrum.hpp"
#include "backends.hpp"
#include "fitlib/fit/problem.hpp"
#include "term_merge.hpp"

namespace fitlib::fit {
namespace {

constexpr double kLogPolishPays = 0.02;  // rms log10 (≈ 5 %) above which the grid's log-space polish runs

// The moduli on the model's log-spaced grid (its start times, over the data window): NNLS, the
// first order of the log10 objective, polished in log space only where the errors are large
// enough for the second order to matter.
FitResult grid_fit(const model::ModelPtr& m, const data::DynamicTestTable& table, const FitOptions& options) {
  FitOptions grid = options;
  grid.backend = Backend::nnls;
  grid.polish = false;
  FitResult fixed = fit(m, table, grid);
  const FitMetrics& lm = fixed.metrics;
  if (options.residual == ResidualKind::log10 && std::max(lm.rms_log10_storage, lm.rms_log10_loss) > kLogPolishPays) {
    grid.polish = true;
    fixed = fit(m, table, grid);
  }
  return fixed;
}

// The moduli by NNLS with the times held at `start`'s, without the assessment of a fit (the
// polish's references and starts: only their cost and values are read).
FitResult linear_solve(const model::ModelPtr& m, const data::DynamicTestTable& table, const FitOptions& options,
                       std::vector<double> start) {
  Problem problem(m, table, options, std::move(start));
  detail::run_nnls(problem);
  FitResult r;
  r.model = m;
  r.values = problem.natural();
  r.metrics.cost = problem.cost(r.values);
  return r;
}

// Every k-th row, k such that at most `per_decade` rows per decade of frequency remain: the
// polish's start only places the times, which a thinned table places as well.
data::DynamicTestTable thinned(const data::DynamicTestTable& table, double decades, double per_decade) {
  const std::size_t k = static_cast<std::size_t>(std::ceil(table.rows.size() / (per_decade * decades)));
  if (k <= 1) return table;
  data::DynamicTestTable t;
  t.source_files = table.source_files;
  for (std::size_t i = 0; i < table.rows.size(); i += k) t.rows.push_back(table.rows[i]);
  return t;
}

// The polish's start: NNLS on a grid of `dense` times (on the table thinned to kStartRowsPerDecade),
// its positive terms merged to `n` by Ward's criterion and the moduli re-solved; the grid's values
// where they cost less on the whole table (or fewer than `n` terms are positive).
constexpr double kStartRowsPerDecade = 20.0;
std::vector<double> merged_start(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                                 const FitOptions& options, int n, int dense, double decades, const FitResult& grid) {
  const model::ModelPtr d = make(dense);
  const data::DynamicTestTable few = thinned(table, decades, kStartRowsPerDecade);
  const FitResult spectrum = linear_solve(d, few, options, d->initial_parameters(summarize(table)));
  const std::vector<detail::Term> terms = detail::positive_terms(spectrum);
  if (static_cast<int>(terms.size()) < n) return grid.values;
  const FitResult merged =
      linear_solve(grid.model, table, options, detail::start_from_terms(*grid.model, spectrum, detail::merge_to(terms, n)));
  return merged.metrics.cost < grid.metrics.cost ? merged.values : grid.values;
}

}  // namespace

std::optional<FitResult> fit_fixed_terms(const std::function<model::ModelPtr(int)>& make,
                                         const data::DynamicTestTable& table, const FitOptions& options, int terms,
                                         const FixedTermOptions& fixed) {
  const std::size_t residuals = 2 * table.rows.size();
  if (options.backend != Backend::automatic || !spectrum_applies(make) || !options.fixed.empty() ||
      residuals < 2 * (2 * static_cast<std::size_t>(terms) + 1))
    return std::nullopt;
  const model::ModelPtr m = make(terms);
  if (m->temperature_law_info().law != model::ShiftLaw::none) return std::nullopt;
  const auto s = summarize(table);
  const double decades = std::max(std::log10(s.omega_max_rad_s / s.omega_min_rad_s), 1e-9);
  const std::string head = "--terms " + std::to_string(terms) + ": ";
  const bool grid_alone = terms >= fixed.grid_per_decade * decades;
  if (grid_alone) {
    FitResult grid = grid_fit(m, table, options);
    grid.messages.push_back(head + "moduli by NNLS on the log-spaced time grid (" + core::format_number(terms / decades, 3) +
                            " terms per decade of the data: free times would not pay)");
    return grid;
  }
  // Where the polish runs, the grid's linear solve is the reference its cost is judged against,
  // fitted and assessed in full only if it is kept.
  FitResult grid = linear_solve(m, table, options, m->initial_parameters(s));
  const int dense = std::max(terms + 1, static_cast<int>(std::ceil(fixed.dense_per_decade * decades)));
  const std::vector<double> start = merged_start(make, table, options, terms, dense, decades, grid);
  FitOptions polish = options;
  polish.max_iterations = std::min(options.max_iterations, fixed.polish_iterations);
  polish.tolerance = std::max(options.tolerance, fixed.polish_tolerance);
  polish.linear_start = false;  // the start's moduli are the NNLS solution at its times already
  polish.descent = LocalDescent::normal_equations;
  FitResult free = fit(m, table, polish, &start);
  const bool keep_free = free.metrics.cost <= (1.0 - fixed.polish_gain) * grid.metrics.cost;
  const double grid_cost = grid.metrics.cost;
  if (!keep_free) grid = grid_fit(m, table, options);
  FitResult& kept = keep_free ? free : grid;
  kept.messages.push_back(head + "NNLS on the log-spaced time grid (cost " + core::format_number(grid_cost, 6) +
                          "), then free times from " + std::to_string(dense) + " NNLS terms merged to " +
                          std::to_string(terms) + " (cost " + core::format_number(free.metrics.cost, 6) + ", " +
                          std::to_string(free.metrics.iterations) + " of at most " +
                          std::to_string(polish.max_iterations) + " iterations): " + (keep_free ? "free" : "grid") +
                          " kept (free times kept when they lower the cost by at least " +
                          core::format_number(100.0 * fixed.polish_gain, 3) + " %; fewer than " +
                          core::format_number(fixed.grid_per_decade, 3) + " terms per decade of the data)");
  return std::move(kept);
}

}  // namespace fitlib::fit
