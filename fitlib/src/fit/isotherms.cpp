// Raw rows → isotherms: grouping by set or temperature, merging duplicates, log-log series.
#include "isotherms.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::fit::detail {
namespace {

void check_temperatures(const data::DynamicTestTable& raw) {
  if (raw.rows.empty()) throw core::UsageError("master curve: the table has no rows");
  for (const auto& row : raw.rows)
    if (!row.condition.has_temperature())
      throw core::InputError("master curve: the row has no temperature (isotherms need temperature_C)",
                             row.source_file, row.source_line);
}

void set_mean_temperature(Isotherm& g, const data::DynamicTestTable& raw) {
  double sum = 0;
  for (int r : g.rows) sum += raw.rows[r].condition.temperature_C;
  g.temperature_C = sum / g.rows.size();
}

// One group per set, in order of first appearance.
std::vector<Isotherm> group_by_set(const data::DynamicTestTable& raw) {
  std::vector<Isotherm> groups;
  std::map<std::string, int> index;
  for (std::size_t i = 0; i < raw.rows.size(); ++i) {
    auto [it, added] = index.emplace(raw.rows[i].set, static_cast<int>(groups.size()));
    if (added) {
      groups.emplace_back();
      groups.back().sets = {raw.rows[i].set};
    }
    groups[it->second].rows.push_back(static_cast<int>(i));
  }
  for (auto& g : groups) set_mean_temperature(g, raw);
  return groups;
}

// One group per cluster of temperatures (neighbours closer than same_temperature_C), labelled
// by its mean temperature.
std::vector<Isotherm> group_by_temperature(const data::DynamicTestTable& raw, double same_temperature_C) {
  std::vector<Isotherm> groups;
  std::vector<int> order(raw.rows.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return raw.rows[a].condition.temperature_C < raw.rows[b].condition.temperature_C;
  });
  double last = -std::numeric_limits<double>::infinity();
  for (int r : order) {
    const double t = raw.rows[r].condition.temperature_C;
    if (t - last >= same_temperature_C) groups.push_back({});
    groups.back().rows.push_back(r);
    last = t;
  }
  for (auto& g : groups) {
    set_mean_temperature(g, raw);
    g.sets = {core::format_number(g.temperature_C, 4) + " C"};
  }
  return groups;
}

// Sorted by temperature; neighbours closer than same_temperature_C become one isotherm.
std::vector<Isotherm> merge_same_temperature(std::vector<Isotherm> groups, double same_temperature_C,
                                             std::vector<std::string>& messages) {
  std::stable_sort(groups.begin(), groups.end(),
                   [](const Isotherm& a, const Isotherm& b) { return a.temperature_C < b.temperature_C; });
  std::vector<Isotherm> merged;
  for (auto& g : groups) {
    if (merged.empty() || g.temperature_C - merged.back().temperature_C >= same_temperature_C) {
      merged.push_back(std::move(g));
      continue;
    }
    auto& m = merged.back();
    messages.push_back("sets " + set_label(m) + " and " + set_label(g) + " have the same temperature (" +
                       core::format_number(m.temperature_C) + " / " + core::format_number(g.temperature_C) +
                       " degC): merged into one isotherm");
    const double n1 = m.rows.size(), n2 = g.rows.size();
    m.temperature_C = (n1 * m.temperature_C + n2 * g.temperature_C) / (n1 + n2);
    m.rows.insert(m.rows.end(), g.rows.begin(), g.rows.end());
    m.sets.insert(m.sets.end(), g.sets.begin(), g.sets.end());
  }
  return merged;
}

}  // namespace

std::string set_label(const Isotherm& iso) {
  std::string s;
  for (const auto& x : iso.sets) s += (s.empty() ? "" : "+") + x;
  return s;
}

std::vector<Isotherm> group_isotherms(const data::DynamicTestTable& raw, const MasterCurveOptions& o,
                                      std::vector<std::string>& messages) {
  check_temperatures(raw);
  const bool any_set = std::any_of(raw.rows.begin(), raw.rows.end(), [](const auto& row) { return !row.set.empty(); });
  auto groups = any_set ? group_by_set(raw) : group_by_temperature(raw, o.same_temperature_C);
  return merge_same_temperature(std::move(groups), o.same_temperature_C, messages);
}

void fill_series(Isotherm& iso, const data::DynamicTestTable& raw, const MasterCurveOptions& o, double reference_C) {
  auto rows = iso.rows;
  std::stable_sort(rows.begin(), rows.end(), [&](int a, int b) {
    return raw.rows[a].condition.frequency_Hz < raw.rows[b].condition.frequency_Hz;
  });
  const double log_b = o.vertical == VerticalShift::entropic
                           ? std::log10(core::kelvin_from_celsius(reference_C) / core::kelvin_from_celsius(iso.temperature_C))
                           : 0.0;
  for (int r : rows) {
    const auto& row = raw.rows[r];
    const double x = std::log10(row.condition.frequency_Hz);
    iso.storage.x.push_back(x);
    iso.storage.y.push_back(std::log10(row.storage_MPa) + log_b);
    iso.loss.x.push_back(x);
    iso.has_loss = iso.has_loss && row.loss_MPa > 0;
    iso.loss.y.push_back(row.loss_MPa > 0 ? std::log10(row.loss_MPa) + log_b : 0.0);
  }
  iso.storage.finish(o.extrapolation_points);
  iso.loss.finish(o.extrapolation_points);
}

int nearest_temperature(const std::vector<double>& temperatures_C, double reference_C) {
  int best = 0;
  for (int k = 1; k < static_cast<int>(temperatures_C.size()); ++k)
    if (std::abs(temperatures_C[k] - reference_C) < std::abs(temperatures_C[best] - reference_C)) best = k;
  return best;
}

}  // namespace fitlib::fit::detail
