#include "quality.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <sstream>

#include "admissible.hpp"
#include "bias_check.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib::fit::detail {
namespace {

// Kramers–Kronig check: loss off by more than this factor where storage is within its threshold.
constexpr double kKramersKronigLossFactor = 1.5;

struct Accumulator {
  int count = 0;
  double sum = 0.0, max = 0.0, max_f = 0.0;
  std::vector<SignedError> signed_errors;  // for the bias check (bias_check.hpp)
  void add(double e, double f, double signed_error) {
    signed_errors.push_back({f, signed_error});
    ++count;
    sum += e;
    if (e > max || count == 1) {  // the first row's frequency when every error is 0
      max = e;
      max_f = f;
    }
  }
};

std::string group_of(const model::TestCondition& c, bool by_temperature, bool by_mode) {
  std::ostringstream s;
  if (by_mode) s << "mode " << model::to_string(c.mode);
  if (by_temperature && c.has_temperature())
    s << (by_mode ? ", " : "") << "T=" << std::round(10.0 * c.temperature_C) / 10.0 << " degC";
  return s.str();
}

std::string percent(double x) {
  std::ostringstream s;
  s.precision(3);
  s << 100.0 * x << " %";
  return s.str();
}

// Kramers–Kronig ranges (docs/decisions.md "Kramers–Kronig inconsistent ranges"): a row is
// flagged where the storage is fitted (within its mean threshold) and the loss it implies misses
// by more than kKramersKronigLossFactor, consistent where both are fitted, neutral where the
// storage is not. A range is a run of at least kKramersKronigRunPoints flagged rows in frequency
// order, within one temperature/mode group; kKramersKronigGap consecutive consistent rows end it.
// One noisy loss point is no range, and the rows between two ranges are not inside one.
constexpr int kKramersKronigRunPoints = 5;
constexpr int kKramersKronigGap = 2;

enum class KramersKronigState { consistent, flagged, neutral };
struct KramersKronigRow {
  double frequency_Hz = 0.0, factor = 1.0;
  KramersKronigState state = KramersKronigState::neutral;
};
struct KramersKronigRange {
  std::string group;
  double lo_Hz = 0.0, hi_Hz = 0.0, worst_factor = 1.0;
};
// group → its rows (group "" when the data have one temperature and one mode)
using KramersKronigRows = std::map<std::string, std::vector<KramersKronigRow>>;

std::vector<KramersKronigRange> kramers_kronig_ranges(const KramersKronigRows& groups) {
  std::vector<KramersKronigRange> out;
  for (const auto& [group, unsorted] : groups) {
    std::vector<KramersKronigRow> rows = unsorted;
    std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.frequency_Hz < b.frequency_Hz; });
    KramersKronigRange range{group};
    int flagged = 0, gap = 0;
    const auto close = [&] {
      if (flagged >= kKramersKronigRunPoints) out.push_back(range);
      flagged = gap = 0;
    };
    for (const auto& r : rows) {
      if (r.state == KramersKronigState::flagged) {
        if (flagged++ == 0) range = {group, r.frequency_Hz, r.frequency_Hz, r.factor};
        range.hi_Hz = r.frequency_Hz;
        range.worst_factor = std::max(range.worst_factor, r.factor);
        gap = 0;
      } else if (r.state == KramersKronigState::consistent && flagged > 0 && ++gap >= kKramersKronigGap) {
        close();
      }
    }
    close();
  }
  return out;
}

// (group, component) → errors; group "" = all rows.
using ErrorGroups = std::map<std::pair<std::string, int>, Accumulator>;

// Groups by temperature when the isotherms differ, by mode when the modes do.
std::pair<bool, bool> grouping(const std::vector<data::DynamicTestRow>& rows) {
  double t_min = INFINITY, t_max = -INFINITY;
  bool mixed_modes = false;
  for (const auto& r : rows) {
    if (r.condition.has_temperature()) {
      t_min = std::min(t_min, r.condition.temperature_C);
      t_max = std::max(t_max, r.condition.temperature_C);
    }
    mixed_modes = mixed_modes || r.condition.mode != rows.front().condition.mode;
  }
  return {t_max - t_min >= kSameTemperature_C, mixed_modes};
}

void accumulate_errors(const Problem& problem, const std::vector<double>& p,
                       const QualityThresholds& th, ErrorGroups& acc, KramersKronigRows& kk) {
  const auto& rows = problem.table().rows;
  const auto [by_temperature, mixed_modes] = grouping(rows);
  int current = -1;
  model::Moduli<double> m{};
  std::vector<double> storage_error(rows.size(), INFINITY);  // INFINITY: no storage residual
  for (const ResidualEntry& e : problem.entries()) {
    const auto& row = rows[e.row];
    if (e.row != current) {
      current = e.row;
      m = problem.model().moduli(p.data(), row.condition);
    }
    // Elastic rows (tan δ below the loss floor) have no relative loss error.
    const bool elastic = e.component == 1 && e.data < Problem::kLossFloor * row.storage_MPa;
    if (elastic || !(e.data > 0.0) || e.sqrt_weight == 0.0) continue;
    const double value = e.component == 0 ? m.storage : e.component == 1 ? m.loss : m.mean;
    const double signed_err = (value - e.data) / e.data;
    const double err = std::abs(signed_err);
    const double f = row.condition.frequency_Hz;
    acc[{"", e.component}].add(err, f, signed_err);
    if (by_temperature || mixed_modes)
      acc[{group_of(row.condition, by_temperature, mixed_modes), e.component}].add(err, f, signed_err);
    if (e.component == 0) storage_error[e.row] = err;
    if (e.component == 1) {
      const double factor = std::max(value / e.data, e.data / value);
      const auto state = storage_error[e.row] > th.storage_mean ? KramersKronigState::neutral
                         : factor > kKramersKronigLossFactor    ? KramersKronigState::flagged
                                                                : KramersKronigState::consistent;
      kk[group_of(row.condition, by_temperature, mixed_modes)].push_back({f, factor, state});
    }
  }
}

// The figures of one (group, component); a warning when they pass the thresholds.
ErrorFigures figures_of(const std::pair<std::string, int>& key, const Accumulator& a,
                        const QualityThresholds& th, std::vector<std::string>& warnings) {
  static const char* names[] = {"storage", "loss", "mean"};
  ErrorFigures fig;
  fig.group = key.first.empty() ? "all" : key.first;
  fig.modulus = names[key.second];
  fig.count = a.count;
  fig.mean_rel_error = a.sum / std::max(a.count, 1);
  fig.max_rel_error = a.max;
  fig.max_at_frequency_Hz = a.max_f;
  const bool loss = key.second == 1;
  const double mean_limit = loss ? th.loss_mean : th.storage_mean;
  const double max_limit = loss ? th.loss_max : th.storage_max;
  if (fig.mean_rel_error > mean_limit || fig.max_rel_error > max_limit) {
    std::ostringstream s;
    s << "fit misses the " << fig.modulus << " modulus (" << fig.group << "): mean relative error "
      << percent(fig.mean_rel_error) << ", max " << percent(fig.max_rel_error) << " at "
      << fig.max_at_frequency_Hz << " Hz (thresholds " << percent(mean_limit) << ", "
      << percent(max_limit) << ")";
    warnings.push_back(s.str());
  }
  return fig;
}

// The ranges in the verdict and one warning naming them.
void kramers_kronig_warning(const std::vector<KramersKronigRange>& ranges, const QualityThresholds& th,
                            QualityVerdict& v) {
  if (ranges.empty()) return;
  std::ostringstream s;
  s << "data not Kramers-Kronig consistent ";
  double worst = 1.0;
  for (std::size_t k = 0; k < ranges.size(); ++k) {
    const auto& r = ranges[k];
    v.kramers_kronig_ranges_Hz.emplace_back(r.lo_Hz, r.hi_Hz);
    worst = std::max(worst, r.worst_factor);
    s << (k ? ", " : "") << "between " << r.lo_Hz << " and " << r.hi_Hz << " Hz" << (r.group.empty() ? "" : " (" + r.group + ")");
  }
  s << ": the storage modulus is fitted within " << percent(th.storage_mean)
    << " there, but the loss modulus it implies differs from the measured one by up to a factor " << worst
    << " (no relaxation spectrum fits both; the weights choose between them)";
  v.warnings.push_back(s.str());
}

}  // namespace

QualityVerdict quality_verdict(const Problem& problem, const std::vector<double>& p,
                               const QualityThresholds& th) {
  ErrorGroups acc;
  KramersKronigRows kk;
  accumulate_errors(problem, p, th, acc, kk);
  QualityVerdict v;
  std::map<int, std::vector<GroupBias>> biased;  // component → its biased groups
  for (const auto& [key, a] : acc) {
    v.figures.push_back(figures_of(key, a, th, v.warnings));
    const double floor = kBiasFloorShare * (key.second == 1 ? th.loss_mean : th.storage_mean);
    if (auto b = group_bias(a.signed_errors, floor)) {
      b->group = key.first.empty() ? "all" : key.first;
      biased[key.second].push_back(*b);
    }
  }
  static const char* names[] = {"storage", "loss", "mean"};
  for (const auto& [component, groups] : biased) v.warnings.push_back(bias_warning(names[component], groups));
  // "all" first, then the groups in their sorted order.
  std::stable_partition(v.figures.begin(), v.figures.end(), [](const ErrorFigures& f) { return f.group == "all"; });
  // A data temperature where the fitted law has no material (its fitter's guard answered there):
  // the card's users (eval, scenes) refuse that temperature.
  std::set<double> temperatures;
  for (const auto& row : problem.table().rows)
    if (row.condition.has_temperature()) temperatures.insert(row.condition.temperature_C);
  for (double T : temperatures) {
    const std::string why = problem.model().temperature_out_of_law(p.data(), T);
    if (why.empty()) continue;
    v.warnings.push_back("the fitted temperature law describes no material at the data's " + core::format_number(T) +
                         " degC, where eval and scenes refuse the card: " + why);
    break;
  }
  if (!series_terms(problem.specs()).empty()) kramers_kronig_warning(kramers_kronig_ranges(kk), th, v);
  return v;
}

void check_single_temperature(const model::Model& model, const data::DynamicTestTable& table) {
  const std::vector<double> p = model.default_parameters();
  const nlohmann::json law = model.temperature_law(p.data());
  if (law.value("law", std::string("none")) != "none" || law.contains("c_T_per_C")) return;
  for (const auto& spec : model.parameters())
    if (spec.group == "shift") return;  // per-isotherm shifts (fit/master_curve.hpp)
  const data::DynamicTestRow* cold = nullptr;
  const data::DynamicTestRow* hot = nullptr;
  for (const auto& r : table.rows) {
    if (!r.condition.has_temperature()) continue;
    if (!cold || r.condition.temperature_C < cold->condition.temperature_C) cold = &r;
    if (!hot || r.condition.temperature_C > hot->condition.temperature_C) hot = &r;
  }
  if (!cold || hot->condition.temperature_C - cold->condition.temperature_C < kSameTemperature_C) return;
  std::ostringstream s;
  s << "rows at " << cold->condition.temperature_C << " degC (" << cold->source_file << ":"
    << cold->source_line << ") and " << hot->condition.temperature_C << " degC (" << hot->source_file
    << ":" << hot->source_line << ") but model '" << model.kind()
    << "' has no temperature law: give --temperature-law wlf|arrhenius (with --reference-c), "
       "or --master-curve for raw isotherms, or fit one temperature at a time";
  throw core::InputError(s.str(), hot->source_file, hot->source_line);
}

void degrees_of_freedom_warning(const FitMetrics& metrics, QualityVerdict& quality) {
  if (metrics.n_free <= 0 || metrics.n_free < metrics.n_residuals) return;
  quality.warnings.push_back("the data do not determine the card: " + std::to_string(metrics.n_residuals) +
                             " residuals for " + std::to_string(metrics.n_free) +
                             " free parameters, so it reproduces the points whatever it is between and beyond "
                             "them; measure more frequencies, times or temperatures, or fit fewer terms");
}

}  // namespace fitlib::fit::detail
