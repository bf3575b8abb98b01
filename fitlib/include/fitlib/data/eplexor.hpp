#pragma once
// Netzsch-Gabo EPLEXOR "Excel Export" (.xls, BIFF in an OLE compound file), read with libfreexl
// (docs/data.md §5). Sheet `Exported Data`: names row, units row, one row per test point; the
// columns f [Hz], T [°C] and E′/E″ (uniaxial) or G′/G″ (shear) [MPa] are used, `---` is a missing
// value. Sheet `Shiftlist` (master-curve exports): reference temperature, WLF C1/C2 and the
// (T, log10 a_T) rows.
#include <limits>
#include <string>

#include "fitlib/data/shift_factors.hpp"
#include "fitlib/data/table.hpp"

namespace fitlib::data {

struct EplexorExport {
  // Rows in sheet order; raw exports get `set` = isotherm index 0, 1, … (a new isotherm starts
  // where the frequency falls), master exports none. source_line = spreadsheet row (1-based).
  DynamicTestTable table;
  bool has_shift_list = false;
  ShiftFactorTable shifts;  // from `Shiftlist`, reference_C from `Ref.Temp.`
  double wlf_C1 = std::numeric_limits<double>::quiet_NaN();
  double wlf_C2_K = std::numeric_limits<double>::quiet_NaN();
};

// True when `bytes` start with the OLE compound-file signature (D0 CF 11 E0 A1 B1 1A E1).
bool is_ole_compound_file(const std::string& bytes);

// Throws core::InputError naming the file, sheet, row and column (line = spreadsheet row,
// column = spreadsheet column, both 1-based). ReadOptions::skip_bad_rows skips rows with a
// missing or bad required value, one warning each.
EplexorExport read_eplexor(const std::string& path, const ReadOptions& options = {});

}  // namespace fitlib::data
