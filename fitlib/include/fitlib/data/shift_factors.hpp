#pragma once
// Time–temperature shift factors as pyvisco writes them (docs/data.md §3): a names row
// `T,log_aT`, a units row `C,-` (or `K,-`), then one row per temperature. log10 a_T is the
// horizontal shift: reduced frequency f·a_T, reduced time t/a_T.
#include <limits>
#include <string>
#include <vector>

namespace fitlib::data {

struct ShiftFactor {
  double temperature_C = 0.0;
  double log10_aT = 0.0;
};

struct ShiftFactorTable {
  // The temperature where log a_T = 0 when the source says so (EPLEXOR `Ref.Temp.`, or a row
  // with log a_T = 0 in a CSV); NaN otherwise.
  double reference_C = std::numeric_limits<double>::quiet_NaN();
  std::vector<ShiftFactor> factors;  // in file order
  std::string source_file;
};

// Reads a pyvisco shift-factor CSV (UTF-8 BOM and CRLF allowed, `#` comment lines skipped).
// Throws core::InputError naming file, line and column.
ShiftFactorTable read_shift_factors(const std::string& path);
ShiftFactorTable parse_shift_factors(const std::string& bytes, const std::string& file_name);

// pyvisco's format: `T,log_aT` / `C,-`, then the rows in shortest round-trip text.
std::string format_shift_factors(const ShiftFactorTable& table);

// log10 a_T at `temperature_C`, linear in T between the two nearest tabulated temperatures;
// outside the table by more than `tolerance_C` a core::InputError naming the file.
double interpolate_log10_aT(const ShiftFactorTable& table, double temperature_C,
                            double tolerance_C = 0.5);

}  // namespace fitlib::data
