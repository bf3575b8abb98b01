#include "fitlib/fit/problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "fitlib/core/error.hpp"

namespace fitlib::fit {

namespace {

constexpr double kLn10 = 2.302585092994046;
constexpr double kInf = std::numeric_limits<double>::infinity();

double component_value(const model::Moduli<double>& m, int component) {
  return component == 0 ? m.storage : component == 1 ? m.loss : m.mean;
}

// The imposed test as an ordered key (NaN, e.g. "reference temperature", as −inf so that equal
// conditions compare equal): the model's moduli are a pure function of it.
using ConditionKey = std::tuple<int, std::string, double, double, double, double>;
ConditionKey condition_key(const model::TestCondition& c) {
  auto key = [](double x) { return std::isnan(x) ? -kInf : x; };
  return {static_cast<int>(c.mode), c.orientation, key(c.frequency_Hz), key(c.temperature_C),
          key(c.strain_amplitude), key(c.mean_strain)};
}

// log10 of a model value; a non-positive value is floored at 1e-12 × the data so the residual
// stays finite and pushes the value back up.
double floored(double value, double data) { return std::max(value, 1e-12 * data); }

// A row's weight and moduli as the residuals need them; the error names its file, line and column.
void check_row(const data::DynamicTestRow& row) {
  if (!(row.weight >= 0.0) || !std::isfinite(row.weight))
    throw core::InputError("row weight must be finite and >= 0", row.source_file,
                           row.source_line, 0, "weight");
  if (!(row.storage_MPa > 0.0) || !std::isfinite(row.storage_MPa))
    throw core::InputError("storage modulus must be positive and finite", row.source_file,
                           row.source_line, 0, "storage");
  if (!(row.loss_MPa >= 0.0) || !std::isfinite(row.loss_MPa))
    throw core::InputError("loss modulus must be >= 0 and finite", row.source_file,
                           row.source_line, 0, "loss");
}

// The residual of component c (0 storage, 1 loss, 2 mean) of row r, measured value `data`.
ResidualEntry entry_of(const data::DynamicTestRow& row, int r, int c, double data, double weight,
                       ResidualKind residual) {
  ResidualEntry e;
  e.row = r;
  e.component = c;
  e.data = data;
  e.sqrt_weight = std::sqrt(weight);
  // Loss below tan δ = 1e-6, or a non-positive mean modulus: absolute residual on E′'s scale.
  const bool tiny = c == 1 ? data < Problem::kLossFloor * row.storage_MPa : !(data > 0.0);
  if (tiny || residual != ResidualKind::log10) {
    e.absolute = true;
    // complex: E′ and E″ errors relative to the row's |E*| (docs/fitting.md "Objective").
    const double ref = residual == ResidualKind::complex && c < 2
                           ? std::hypot(row.storage_MPa, row.loss_MPa)
                       : tiny ? row.storage_MPa
                              : data;
    e.scale = residual == ResidualKind::log10 ? ref * kLn10 : ref;
  }
  return e;
}

}  // namespace

const char* component_name(int component) {
  return component == 0 ? "storage" : component == 1 ? "loss" : "mean";
}

Problem::Problem(model::ModelPtr model, const data::DynamicTestTable& table, FitOptions options,
                 std::vector<double> natural_start)
    : model_(std::move(model)), table_(&table), options_(std::move(options)),
      natural_(std::move(natural_start)) {
  const auto& sp = specs();
  const int n = static_cast<int>(sp.size());
  if (static_cast<int>(natural_.size()) != n)
    throw core::UsageError("fit: start vector has " + std::to_string(natural_.size()) +
                           " values, model '" + model_->kind() + "' has " + std::to_string(n) +
                           " parameters");
  if (table.rows.empty()) throw core::UsageError("fit: the data table has no rows");
  const double weights[3] = {options_.storage_weight, options_.loss_weight, options_.mean_weight};
  for (double w : weights)
    if (!(w >= 0.0) || !std::isfinite(w))
      throw core::UsageError("fit: storage/loss/mean weights must be finite and >= 0");

  for (int r = 0; r < static_cast<int>(table.rows.size()); ++r) {
    const auto& row = table.rows[r];
    check_row(row);
    const double values[3] = {row.storage_MPa, row.loss_MPa, row.mean_modulus_MPa};
    for (int c = 0; c < 3; ++c) {
      if (c == 2 && !row.has_mean_modulus) continue;
      const double w = row.weight * weights[c];
      if (w == 0.0) continue;
      entries_.push_back(entry_of(row, r, c, values[c], w, options_.residual));
    }
  }
  if (entries_.empty()) throw core::UsageError("fit: every residual has zero weight");
  std::map<ConditionKey, int> distinct;
  condition_of_row_.resize(table.rows.size());
  for (int r = 0; r < static_cast<int>(table.rows.size()); ++r) {
    const auto [it, added] = distinct.try_emplace(condition_key(table.rows[r].condition),
                                                  static_cast<int>(distinct_rows_.size()));
    if (added) distinct_rows_.push_back(r);
    condition_of_row_[r] = it->second;
  }

  lower_.resize(n);
  upper_.resize(n);
  user_fixed_.assign(n, false);
  for (int i = 0; i < n; ++i) {
    lower_[i] = sp[i].lower;
    upper_[i] = sp[i].upper;
    if (sp[i].transform == core::Transform::log) lower_[i] = std::max(lower_[i], 0.0);
  }
  for (const auto& name : options_.fixed) {
    const int i = core::find_parameter(sp, name);
    if (i < 0) throw core::UsageError("fit: no parameter named '" + name + "' to fix in model '" +
                                      model_->kind() + "'");
    user_fixed_[i] = true;
  }
  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (!user_fixed_[i]) free.push_back(i);
  set_free(std::move(free));
  tighten_temperature_bounds();
  clamp_start();
}

void Problem::set_free(std::vector<int> free) {
  free_ = std::move(free);
}

bool Problem::restrict_bounds(int i, double lower, double upper) {
  lower_[i] = std::max(lower, specs()[i].transform == core::Transform::log ? 0.0 : specs()[i].lower);
  upper_[i] = std::min(upper, specs()[i].upper);
  const double before = natural_[i];
  natural_[i] = std::clamp(natural_[i], lower_[i], upper_[i]);
  return natural_[i] != before;
}

bool Problem::is_log(int i) const { return specs()[i].transform == core::Transform::log; }

// WLF: log aT = −C1 (T − Tref)/(C2 + T − Tref) has a pole at T = Tref − C2 (docs/decisions.md,
// "fit: WLF pole"); the model names the pole's parameter (TemperatureLawInfo::pole_parameter).
// Keep every data temperature on the physical side: C2 > max(Tref − T_i) (+1 °C margin).
void Problem::tighten_temperature_bounds() {
  const model::TemperatureLawInfo law = model_->temperature_law_info();
  const int c2 = law.pole_parameter;
  if (c2 < 0) return;
  const double t_ref = law.reference_C;
  double max_gap = -kInf;
  for (const auto& row : table_->rows)
    if (row.condition.has_temperature())
      max_gap = std::max(max_gap, t_ref - row.condition.temperature_C);
  if (!std::isfinite(max_gap)) return;
  const double bound = max_gap + 1.0;
  if (natural_[c2] <= bound && !user_fixed_[c2]) {
    // A start just inside the bound would put the coldest rows next to the pole (a_T → ∞).
    const double start = 1.5 * max_gap + 10.0;
    std::ostringstream s;
    s << "WLF: start of " << specs()[c2].name << " moved from " << natural_[c2] << " to " << start
      << " degC, clear of the pole at the coldest data";
    notes_.push_back(s.str());
    natural_[c2] = start;
  }
  if (bound > lower_[c2]) {
    lower_[c2] = bound;
    std::ostringstream s;
    s << "WLF: lower bound of " << specs()[c2].name << " set to " << bound
      << " degC so the pole T_ref - C2 stays below the coldest data (T_ref - T_min = " << max_gap
      << " degC, margin 1 degC)";
    notes_.push_back(s.str());
  }
}

// Starts strictly inside the bounds (a log parameter cannot start at 0).
void Problem::clamp_start() {
  for (int i = 0; i < num_parameters(); ++i) {
    double& v = natural_[i];
    const double lo = lower_[i], hi = upper_[i];
    if (!std::isfinite(v))
      throw core::UsageError("fit: start value of '" + specs()[i].name + "' is not finite");
    double clamped = v;
    if (is_log(i) && clamped <= 0.0)
      clamped = std::isfinite(hi) ? std::min(1e-3 * hi, 1.0) : std::max(lo, 1.0);
    if (clamped <= lo) {
      const double span = std::isfinite(hi) ? hi - lo : std::max(std::abs(lo), 1.0);
      clamped = is_log(i) && lo > 0 ? lo * 1.01 : lo + 0.01 * span;
    }
    if (clamped >= hi) {
      const double span = std::isfinite(lo) ? hi - lo : std::max(std::abs(hi), 1.0);
      clamped = is_log(i) ? hi * 0.99 : hi - 0.01 * span;
    }
    if (clamped != v && !user_fixed_[i]) {
      std::ostringstream s;
      s << "start of " << specs()[i].name << " moved from " << v << " to " << clamped
        << " (inside its bounds [" << lo << ", " << hi << "])";
      notes_.push_back(s.str());
      v = clamped;
    }
  }
}

Eigen::VectorXd Problem::to_x(const std::vector<double>& natural) const {
  Eigen::VectorXd x(num_free());
  for (int k = 0; k < num_free(); ++k) {
    const int i = free_[k];
    x[k] = is_log(i) ? std::log(natural[i]) : natural[i];
  }
  return x;
}

void Problem::from_x(const double* x, std::vector<double>& natural) const {
  for (int k = 0; k < num_free(); ++k) {
    const int i = free_[k];
    natural[i] = is_log(i) ? std::exp(x[k]) : x[k];
  }
}

double Problem::lower_x(int k) const {
  const int i = free_[k];
  if (is_log(i)) return lower_[i] > 0.0 ? std::log(lower_[i]) : -kInf;
  return lower_[i];
}

double Problem::upper_x(int k) const {
  const int i = free_[k];
  if (is_log(i)) return std::isfinite(upper_[i]) ? std::log(upper_[i]) : kInf;
  return upper_[i];
}

bool Problem::evaluate(const std::vector<double>& natural, double* residuals,
                       double* jacobian) const {
  // A model may refuse a point (e.g. a temperature beyond the WLF pole): that point is simply
  // not usable and the optimiser backs off; diagnose() says why.
  try {
    return evaluate_unchecked(natural, residuals, jacobian);
  } catch (const core::InputError&) {
  } catch (const core::NumericalError&) {
  }
  return false;
}

bool Problem::evaluate_unchecked(const std::vector<double>& natural, double* residuals,
                                 double* jacobian) const {
  const int n = num_parameters(), nf = num_free();
  const int nd = static_cast<int>(distinct_rows_.size());
  // One model evaluation per distinct condition, shared by the rows that repeat it.
  std::vector<model::Moduli<double>> moduli(nd);
  Eigen::MatrixXd jacs(3, jacobian ? static_cast<Eigen::Index>(n) * nd : 0);
  for (int d = 0; d < nd; ++d) {
    const auto& c = table_->rows[distinct_rows_[d]].condition;
    if (!jacobian) {
      moduli[d] = model_->moduli(natural.data(), c);
      continue;
    }
    auto jac = jacs.middleCols(static_cast<Eigen::Index>(d) * n, n);
    moduli[d] = model_->moduli(natural.data(), c, jac);
  }
  // dp/dx of each free parameter (p = exp(x) for log-transformed ones), once per evaluation.
  std::vector<double> chain(nf);
  for (int k = 0; k < nf; ++k) chain[k] = is_log(free_[k]) ? natural[free_[k]] : 1.0;
  for (int e = 0; e < num_residuals(); ++e) {
    const ResidualEntry& en = entries_[e];
    const int d = condition_of_row_[en.row];
    const double value = component_value(moduli[d], en.component);
    double r, dr_dm;
    if (en.absolute) {
      r = (value - en.data) / en.scale;
      dr_dm = 1.0 / en.scale;
    } else {
      const double v = floored(value, en.data);
      r = std::log10(v / en.data);
      dr_dm = 1.0 / (v * kLn10);
    }
    residuals[e] = en.sqrt_weight * r;
    if (!std::isfinite(residuals[e])) return false;
    if (jacobian) {
      double* jrow = jacobian + static_cast<std::ptrdiff_t>(e) * nf;
      const double factor = en.sqrt_weight * dr_dm;
      const double* dm_dp = &jacs(en.component, static_cast<Eigen::Index>(d) * n);
      bool finite = true;
      for (int k = 0; k < nf; ++k) {
        jrow[k] = factor * dm_dp[3 * free_[k]] * chain[k];
        finite &= std::isfinite(jrow[k]);
      }
      if (!finite) return false;
    }
  }
  return true;
}

std::string Problem::diagnose(const std::vector<double>& natural) const {
  for (const auto& row : table_->rows) {
    std::string why;
    try {
      const auto m = model_->moduli(natural.data(), row.condition);
      if (!std::isfinite(m.storage) || !std::isfinite(m.loss) || !std::isfinite(m.mean))
        why = "non-finite moduli";
    } catch (const core::InputError& e) {
      why = e.what();
    } catch (const core::NumericalError& e) {
      why = e.what();
    }
    if (why.empty()) continue;
    std::ostringstream s;
    s << why << " at frequency " << row.condition.frequency_Hz << " Hz";
    if (row.condition.has_temperature()) s << ", temperature " << row.condition.temperature_C << " degC";
    if (!row.source_file.empty()) s << " (" << row.source_file << ":" << row.source_line << ")";
    return s.str();
  }
  return "a residual is not finite";
}

double Problem::cost(const std::vector<double>& natural) const {
  std::vector<double> r(num_residuals());
  if (!evaluate(natural, r.data(), nullptr)) return kInf;
  double s = 0.0;
  for (double v : r) s += v * v;
  return 0.5 * s;
}

void Problem::measure(const std::vector<double>& natural, FitMetrics& metrics) const {
  double sum_storage = 0.0, sum_loss = 0.0, sum_rel = 0.0, max_rel = 0.0;
  int n_storage = 0, n_loss = 0, n_rel = 0;
  auto relative = [&](double model, double data) {
    const double rel = std::abs(model - data) / data;
    sum_rel += rel;
    max_rel = std::max(max_rel, rel);
    ++n_rel;
  };
  auto log_error = [](double model, double data) {
    const double d = std::log10(floored(model, data) / data);
    return d * d;
  };
  for (const auto& row : table_->rows) {
    const auto m = model_->moduli(natural.data(), row.condition);
    sum_storage += log_error(m.storage, row.storage_MPa);
    ++n_storage;
    relative(m.storage, row.storage_MPa);
    if (row.loss_MPa >= kLossFloor * row.storage_MPa) {
      sum_loss += log_error(m.loss, row.loss_MPa);
      ++n_loss;
      relative(m.loss, row.loss_MPa);
    }
    if (row.has_mean_modulus && row.mean_modulus_MPa > 0.0) relative(m.mean, row.mean_modulus_MPa);
  }
  metrics.n_points = static_cast<int>(table_->rows.size());
  metrics.rms_log10_storage = n_storage ? std::sqrt(sum_storage / n_storage) : 0.0;
  metrics.rms_log10_loss = n_loss ? std::sqrt(sum_loss / n_loss) : 0.0;
  metrics.mean_rel_error = n_rel ? sum_rel / n_rel : 0.0;
  metrics.max_rel_error = max_rel;
}

}  // namespace fitlib::fit
