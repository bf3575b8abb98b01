#pragma once
// Relaxation tests (docs/data.md §4): modulus after a strain step, M(t) = E(t) or G(t), MPa.
// pyvisco's CSV: names row `t, E_relax[, T, Set]` (or `G_relax`), units row `s, MPa[, C, -]`.
#include <limits>
#include <string>
#include <vector>

#include "fitlib/core/test_condition.hpp"

namespace fitlib::data {

struct RelaxationRow {
  core::TestMode mode = core::TestMode::uniaxial;  // E → uniaxial, G → shear
  double time_s = 0.0;
  double modulus_MPa = 0.0;
  double temperature_C = std::numeric_limits<double>::quiet_NaN();  // NaN: the reference
  double weight = 1.0;
  std::string set;
  std::string source_file;
  int source_line = 0;
};

struct RelaxationTable {
  std::vector<RelaxationRow> rows;
  std::vector<std::string> source_files;
  std::vector<std::string> source_sha256;
};

// True when the first content line of `bytes` is a pyvisco time-domain header (first field `t`).
bool looks_like_relaxation_csv(const std::string& bytes);

// Reads pyvisco's time-domain CSV. Throws core::InputError naming file, line and column.
RelaxationTable read_relaxation_table(const std::string& path);
RelaxationTable parse_relaxation_table(const std::string& bytes, const std::string& file_name);

}  // namespace fitlib::data
