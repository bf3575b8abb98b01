#pragma once
// Checks on an accepted dynamic-test table, shared by the native and pyvisco harnesses: every
// number finite (temperature may be absent = NaN), and the native text written for it reads back
// to bit-identical values (the promise of format_dynamic_table).
#include <cstring>

#include "fitlib/data/eplexor.hpp"
#include "fitlib/data/table.hpp"
#include "fuzz_common.hpp"

namespace fitlib::fuzz {

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline void check_table(const data::DynamicTestTable& table) {
  for (const auto& row : table.rows) {
    const auto& c = row.condition;
    require_finite(c.frequency_Hz, "frequency");
    if (c.has_temperature()) require_finite(c.temperature_C, "temperature");
    require_finite(c.strain_amplitude, "strain amplitude");
    require_finite(c.mean_strain, "mean strain");
    require_finite(row.storage_MPa, "storage modulus");
    require_finite(row.loss_MPa, "loss modulus");
    if (row.has_mean_modulus) require_finite(row.mean_modulus_MPa, "mean modulus");
    require_finite(row.weight, "weight");
  }
  if (table.rows.empty()) return;
  const auto again = data::parse_dynamic_table(data::format_dynamic_table(table), "written.csv");
  if (again.rows.size() != table.rows.size()) finding("written table reads back with another row count");
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const auto& a = table.rows[i];
    const auto& b = again.rows[i];
    if (!same_bits(a.storage_MPa, b.storage_MPa) || !same_bits(a.loss_MPa, b.loss_MPa) ||
        !same_bits(a.condition.frequency_Hz, b.condition.frequency_Hz) ||
        a.condition.mode != b.condition.mode || a.material != b.material ||
        a.specimen != b.specimen || a.set != b.set)
      finding("written table does not read back to the same values (row " + std::to_string(i) + ")");
  }
}

// An accepted EPLEXOR export: the table as above, the shift list finite.
inline void check_eplexor(const data::EplexorExport& exported) {
  check_table(exported.table);
  if (!exported.has_shift_list) return;
  require_finite(exported.shifts.reference_C, "EPLEXOR Ref.Temp.");
  for (const auto& s : exported.shifts.factors) {
    require_finite(s.temperature_C, "shift temperature");
    require_finite(s.log10_aT, "log10 a_T");
  }
}

}  // namespace fitlib::fuzz
