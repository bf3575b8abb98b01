// EPLEXOR .xls exports through libfreexl (docs/data.md §5).
#include "fitlib/data/eplexor.hpp"

#include <charconv>
#include <cmath>
#include <optional>
#include <vector>

#include "eplexor_cells.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::data {
namespace {

constexpr const char* kDataSheet = "Exported Data";
constexpr const char* kShiftSheet = "Shiftlist";

// "A".."Z", "AA".. for messages (spreadsheet column of 0-based index).
std::string column_letters(unsigned column) {
  std::string s;
  for (unsigned c = column + 1; c > 0; c = (c - 1) / 26) s.insert(s.begin(), static_cast<char>('A' + (c - 1) % 26));
  return s;
}

// One workbook's sheets, read by libfreexl in a child process (eplexor_cells.hpp); cells as text
// or number.
class Workbook {
 public:
  Workbook(const std::string& path, std::vector<xls::Sheet> sheets)
      : path_(path), sheets_(std::move(sheets)) {}

  // Selects the sheet called `name`; false if there is none.
  bool select(const std::string& name) {
    for (const auto& sheet : sheets_)
      if (sheet.name == name) {
        sheet_ = &sheet;
        return true;
      }
    return false;
  }
  unsigned rows() const { return sheet_->rows; }
  unsigned columns() const { return sheet_->columns; }

  // Text of a cell ("" when empty or a real number); numbers also in `number`.
  std::string text(unsigned row, unsigned column, std::optional<double>* number = nullptr) const {
    if (number) number->reset();
    const auto at = sheet_->cells.find({row, column});
    if (at == sheet_->cells.end()) return "";
    const xls::Cell& cell = at->second;
    if (cell.kind == xls::Cell::Kind::text) return cell.text;
    if (number) *number = cell.number;
    return cell.kind == xls::Cell::Kind::integer ? std::to_string(static_cast<int>(cell.number)) : "";
  }

  core::InputError error(const std::string& message, unsigned row, std::optional<unsigned> column = {},
                         const std::string& column_name = {}) const {
    std::string where = "sheet '" + sheet_->name + "'";
    if (column) where += ", column " + column_letters(*column) + (column_name.empty() ? "" : " '" + column_name + "'");
    return core::InputError(where + ": " + message, path_, static_cast<int>(row) + 1,
                            column ? static_cast<int>(*column) + 1 : 0);
  }

  // A finite number in a cell; `---`, empty or text is an error naming the cell.
  double number(unsigned row, unsigned column, const std::string& name) const {
    std::optional<double> value;
    const std::string t = text(row, column, &value);
    if (!value) {
      double parsed = 0.0;
      const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), parsed);
      if (ec == std::errc() && ptr == t.data() + t.size() && !t.empty()) value = parsed;
    }
    if (!value)
      throw error(t == "---" || t.empty() ? "missing value ('" + t + "')" : "'" + t + "' is not a number", row, column,
                  name);
    if (!std::isfinite(*value)) throw error("value is not finite", row, column, name);
    return *value;
  }

 private:
  std::string path_;
  std::vector<xls::Sheet> sheets_;
  const xls::Sheet* sheet_ = nullptr;
};

// Finite number after "<label> :" in texts such as "C1 : 13.50" or "25.0 °C"; nullopt if none
// (from_chars also reads "inf" and "nan").
std::optional<double> leading_number(const std::string& text) {
  std::size_t start = text.find(':');
  start = start == std::string::npos ? 0 : start + 1;
  while (start < text.size() && text[start] == ' ') ++start;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data() + start, text.data() + text.size(), value);
  if (ec != std::errc() || ptr == text.data() + start || !std::isfinite(value)) return std::nullopt;
  return value;
}

void read_shift_list(Workbook& book, EplexorExport& out, const std::string& path) {
  out.has_shift_list = true;
  out.shifts.source_file = path;
  unsigned row = 0;
  for (; row < book.rows(); ++row) {
    const std::string label = book.text(row, 0);
    if (label == "Ref.Temp.") {
      const auto t = leading_number(book.text(row, 1));
      if (!t) throw book.error("reference temperature '" + book.text(row, 1) + "' is not a finite number", row, 1u);
      out.shifts.reference_C = *t;
    } else if (label == "WLF") {
      if (const auto c1 = leading_number(book.text(row, 1))) out.wlf_C1 = *c1;
      if (const auto c2 = leading_number(book.text(row, 2))) out.wlf_C2_K = *c2;
    } else if (label == "Temp.") {
      ++row;
      break;
    }
  }
  for (; row < book.rows(); ++row) {
    if (book.text(row, 0).empty() && book.text(row, 1).empty()) {
      std::optional<double> v;
      book.text(row, 0, &v);
      if (!v) continue;  // blank row
    }
    ShiftFactor s;
    s.temperature_C = book.number(row, 0, "Temp.");
    s.log10_aT = book.number(row, 1, "Shift");
    out.shifts.factors.push_back(s);
  }
  if (out.shifts.factors.empty()) throw book.error("no 'Temp.' / 'Shift' rows", row);
  if (std::isnan(out.shifts.reference_C)) throw book.error("no 'Ref.Temp.' row before 'Temp.'", 0);
}

}  // namespace

bool is_ole_compound_file(const std::string& bytes) {
  static const unsigned char kMagic[] = {0xD0, 0xCF, 0x11, 0xE0, 0xA1, 0xB1, 0x1A, 0xE1};
  if (bytes.size() < sizeof kMagic) return false;
  for (std::size_t i = 0; i < sizeof kMagic; ++i)
    if (static_cast<unsigned char>(bytes[i]) != kMagic[i]) return false;
  return true;
}

namespace {

// The data sheet's columns (field indices; T < 0 when absent), test mode and unit factors.
struct DataColumns {
  int f = -1, T = -1, storage = -1, loss = -1;
  core::TestMode mode = core::TestMode::uniaxial;
  double to_MPa[2];  // storage, loss
};

// Names in row 0, units in row 1.
DataColumns locate_columns(Workbook& book) {
  DataColumns d;
  for (unsigned c = 0; c < book.columns(); ++c) {
    const std::string name = book.text(0, c);
    const auto take = [&](int& slot) {
      if (slot >= 0) throw book.error("duplicate column '" + name + "'", 0, c);
      slot = static_cast<int>(c);
    };
    if (name == "f") take(d.f);
    else if (name == "T") take(d.T);
    else if (name == "E'" || name == "G'") take(d.storage), d.mode = name[0] == 'G' ? core::TestMode::shear : d.mode;
    else if (name == "E''" || name == "G''") take(d.loss);
  }
  if (d.f < 0) throw book.error("missing column 'f'", 0);
  if (d.storage < 0) throw book.error("missing column E' (or G')", 0);
  if (d.loss < 0) throw book.error("missing column E'' (or G'')", 0);
  const auto unit_of = [&](int c) { return book.text(1, static_cast<unsigned>(c)); };
  if (unit_of(d.f) != "Hz") throw book.error("unit '" + unit_of(d.f) + "' of column 'f' (expected Hz)", 1, d.f);
  for (int k = 0; k < 2; ++k) {
    const int c = k == 0 ? d.storage : d.loss;
    try {
      d.to_MPa[k] = core::modulus_to_MPa(unit_of(c));
    } catch (const core::InputError&) {
      throw book.error("unit '" + unit_of(c) + "' (expected Pa, kPa, MPa or GPa)", 1, c);
    }
  }
  if (d.T >= 0 && unit_of(d.T) != "°C") throw book.error("unit '" + unit_of(d.T) + "' of column 'T' (expected °C)", 1, d.T);
  return d;
}

DynamicTestRow read_data_row(Workbook& book, const DataColumns& d, unsigned r,
                             const std::string& path) {
  DynamicTestRow row;
  row.source_file = path;
  row.source_line = static_cast<int>(r) + 1;
  row.condition.mode = d.mode;
  row.condition.frequency_Hz = book.number(r, d.f, "f");
  if (!(row.condition.frequency_Hz > 0.0)) throw book.error("non-positive frequency", r, d.f, "f");
  row.storage_MPa = book.number(r, d.storage, book.text(0, d.storage)) * d.to_MPa[0];
  if (!(row.storage_MPa > 0.0)) throw book.error("non-positive storage modulus", r, d.storage, book.text(0, d.storage));
  row.loss_MPa = book.number(r, d.loss, book.text(0, d.loss)) * d.to_MPa[1];
  if (row.loss_MPa < 0.0) throw book.error("negative loss modulus", r, d.loss, book.text(0, d.loss));
  if (d.T >= 0) {
    row.condition.temperature_C = book.number(r, d.T, "T");
    if (!(row.condition.temperature_C > -core::kZeroCelsiusInKelvin))
      throw book.error("temperature below absolute zero", r, d.T, "T");
  }
  return row;
}

}  // namespace

EplexorExport read_eplexor(const std::string& path, const ReadOptions& options) {
  const std::string bytes = core::read_file(path);
  if (!is_ole_compound_file(bytes)) throw core::InputError("not an .xls (OLE compound) file", path);
  EplexorExport out = xls::eplexor_from_sheets(xls::read_sheets(path, {kShiftSheet, kDataSheet}), path, options);
  out.table.source_sha256.push_back(core::sha256_hex(bytes));
  return out;
}

EplexorExport xls::eplexor_from_sheets(std::vector<Sheet> sheets, const std::string& path,
                                       const ReadOptions& options) {
  EplexorExport out;
  DynamicTestTable& table = out.table;
  table.source_files.push_back(path);
  Workbook book(path, std::move(sheets));
  if (book.select(kShiftSheet)) read_shift_list(book, out, path);
  if (!book.select(kDataSheet)) throw core::InputError(std::string("no sheet '") + kDataSheet + "'", path);
  if (book.rows() < 3) throw book.error("needs a names row, a units row and data rows", book.rows());
  const DataColumns columns = locate_columns(book);

  int isotherm = 0;
  double previous_f = 0.0;
  for (unsigned r = 2; r < book.rows(); ++r) {
    try {
      DynamicTestRow row = read_data_row(book, columns, r, path);
      if (!out.has_shift_list) {
        // A raw temperature–frequency sweep: each isotherm starts again at the lowest frequency.
        if (!table.rows.empty() && row.condition.frequency_Hz < previous_f) ++isotherm;
        previous_f = row.condition.frequency_Hz;
        row.set = std::to_string(isotherm);
      }
      table.rows.push_back(std::move(row));
    } catch (const core::InputError& e) {
      if (!options.skip_bad_rows) throw;
      table.warnings.push_back(std::string("skipped row: ") + e.what());
    }
  }
  if (table.rows.empty()) throw book.error("no valid data rows", 1);
  return out;
}

}  // namespace fitlib::data
