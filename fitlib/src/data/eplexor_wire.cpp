// The sheets of an .xls workbook as bytes, from the libfreexl child to fitlib (eplexor_cells.hpp).
// Both ends are the same binary, so numbers go in native byte order. Records: 'S' name rows columns
// (a sheet; the cells after it are its own), 'C' row column kind value (a cell: an 8-byte double or
// a text), 'E' code (libfreexl refused the file), 'Z' (the end: a stream without it is truncated).
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "eplexor_cells.hpp"
#include "fitlib/core/error.hpp"

namespace fitlib::data::xls {
namespace {

class Writer {
 public:
  template <class T>
  void put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void put(const std::string& text) {
    put(static_cast<std::uint32_t>(text.size()));
    bytes_ += text;
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class Reader {
 public:
  Reader(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}
  template <class T>
  T get() {
    T value;
    need(sizeof value);
    std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
    return value;
  }
  std::string text() {
    const auto size = get<std::uint32_t>();
    need(size);
    at_ += size;
    return bytes_.substr(at_ - size, size);
  }
  [[noreturn]] void fail() const {
    throw core::InputError("libfreexl could not read it (its reader process gave a malformed answer)", path_);
  }

 private:
  void need(std::size_t size) const {
    if (size > bytes_.size() - at_) fail();
  }
  const std::string& bytes_;
  const std::string& path_;
  std::size_t at_ = 0;
};

}  // namespace

std::string serialize_sheets(const std::vector<Sheet>& sheets) {
  Writer w;
  for (const auto& sheet : sheets) {
    w.put('S'), w.put(sheet.name), w.put(std::uint32_t{sheet.rows}), w.put(std::uint32_t{sheet.columns});
    for (const auto& [at, cell] : sheet.cells) {
      w.put('C'), w.put(std::uint32_t{at.first}), w.put(std::uint32_t{at.second}), w.put(cell.kind);
      if (cell.kind == Cell::Kind::text) w.put(cell.text);
      else w.put(cell.number);
    }
  }
  w.put('Z');
  return w.take();
}

std::string serialize_refusal(int freexl_error) {
  Writer w;
  w.put('E'), w.put(std::int32_t{freexl_error}), w.put('Z');
  return w.take();
}

namespace {
bool is_int32(double x) {
  return x == std::floor(x) && x >= std::numeric_limits<std::int32_t>::min() &&
         x <= std::numeric_limits<std::int32_t>::max();
}
}  // namespace

std::vector<Sheet> parse_sheets(const std::string& bytes, const std::string& path) {
  Reader r(bytes, path);
  std::vector<Sheet> sheets;
  for (;;) {
    const char tag = r.get<char>();
    if (tag == 'Z') return sheets;
    if (tag == 'E') {
      const std::int32_t code = r.get<std::int32_t>();
      throw core::InputError("not a readable .xls workbook (libfreexl error " + std::to_string(code) + ")", path);
    }
    if (tag == 'S') {
      Sheet& s = sheets.emplace_back();
      s.name = r.text(), s.rows = r.get<std::uint32_t>(), s.columns = r.get<std::uint32_t>();
      // The readers loop over the claimed dimensions: hold them to BIFF8's (a malformed DIMENSION
      // record may claim 2^32 rows).
      if (s.rows > kMaxRows || s.columns > kMaxColumns)
        throw core::InputError("sheet '" + s.name + "' claims " + std::to_string(s.rows) + " rows x " +
                                   std::to_string(s.columns) + " columns, beyond the .xls limits (" +
                                   std::to_string(kMaxRows) + " x " + std::to_string(kMaxColumns) + ")",
                               path);
      continue;
    }
    if (tag != 'C' || sheets.empty()) r.fail();
    const auto row = r.get<std::uint32_t>(), column = r.get<std::uint32_t>();
    Cell cell;
    cell.kind = r.get<Cell::Kind>();
    if (cell.kind == Cell::Kind::text) cell.text = r.text();
    else if (cell.kind == Cell::Kind::integer || cell.kind == Cell::Kind::real) cell.number = r.get<double>();
    else r.fail();
    if (cell.kind == Cell::Kind::integer && !is_int32(cell.number)) r.fail();  // libfreexl's int
    sheets.back().cells[{row, column}] = std::move(cell);
  }
}

}  // namespace fitlib::data::xls
