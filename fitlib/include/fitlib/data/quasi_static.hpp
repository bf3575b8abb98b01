#pragma once
// Quasi-static test tables (docs/formats.md §"Quasi-static tests"): stress–stretch points of
// homogeneous tests for hyperelastic fits. CSV with a header row:
//   mode,stretch,nominal_stress_MPa                        (uniaxial, equibiaxial, planar)
//   mode,shear_strain,nominal_stress_MPa                   (simple_shear)
//   mode,volume_ratio,pressure_MPa                         (volumetric)
// in one file, each row filling the columns of its mode and leaving the others empty; optional
// specimen, temperature_C, strain_rate_per_s. `strain` (λ − 1) or `strain_percent` (100 (λ − 1))
// may replace `stretch`: the header says which.
#include <limits>
#include <string>
#include <vector>

#include "fitlib/core/deformation_mode.hpp"

namespace fitlib::data {

struct QuasiStaticRow {
  core::DeformationMode mode = core::DeformationMode::uniaxial;
  double abscissa = 1.0;   // stretch λ, shear strain γ or volume ratio J (core::abscissa_name)
  double stress_MPa = 0.0;  // nominal stress P11 (P12 in simple shear) or the pressure
  std::string specimen;
  double temperature_C = std::numeric_limits<double>::quiet_NaN();     // NaN: not given
  double strain_rate_per_s = std::numeric_limits<double>::quiet_NaN();  // NaN: not given
  std::string source_file;
  int source_line = 0;
};

struct QuasiStaticTable {
  std::vector<QuasiStaticRow> rows;
  std::vector<std::string> source_files;
  std::vector<std::string> source_sha256;
};

// True when the first content line is a quasi-static header: a `mode` column and one of the
// abscissa columns (stretch, strain, strain_percent, shear_strain, volume_ratio).
bool looks_like_quasi_static_csv(const std::string& bytes);

// Reads a quasi-static table. Throws core::InputError naming file, line and column.
QuasiStaticTable read_quasi_static_table(const std::string& path);
QuasiStaticTable parse_quasi_static_table(const std::string& bytes, const std::string& file_name);
// The rows of several tables in one (files in order).
QuasiStaticTable merge_quasi_static_tables(const std::vector<QuasiStaticTable>& tables);

}  // namespace fitlib::data
