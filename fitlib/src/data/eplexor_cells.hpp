#pragma once
// The cells of an .xls workbook, read by libfreexl in a child process (docs/decisions.md "data:
// EPLEXOR workbooks are read by libfreexl in a child process"): Debian's libfreexl 1.0.6 overreads
// a stack buffer on some malformed workbooks (docs/reliability.md §2), so whatever it does to its
// process must not happen to fitlib's.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fitlib/data/eplexor.hpp"

namespace fitlib::data::xls {

struct Cell {
  enum class Kind : std::uint8_t { integer = 'I', real = 'D', text = 'T' };
  Kind kind = Kind::text;
  double number = 0.0;  // integer and real cells
  std::string text;     // text cells (dates and times too, as libfreexl gives them)
};

// BIFF8's sheet limits (.xls, Excel 97–2003): parse_sheets refuses larger claimed dimensions.
constexpr unsigned kMaxRows = 65536, kMaxColumns = 256;

struct Sheet {
  std::string name;
  unsigned rows = 0, columns = 0;                       // libfreexl's worksheet dimensions
  std::map<std::pair<unsigned, unsigned>, Cell> cells;  // (row, column), 0-based → non-empty cell
};

// The sheets of the workbook at `path` whose names are in `names`, in workbook order. Throws
// core::InputError naming the file when libfreexl refuses the file or its process does not end
// normally (a signal, a sanitizer report, an incomplete answer).
std::vector<Sheet> read_sheets(const std::string& path, const std::vector<std::string>& names);

// The bytes `answer` returns when run in a child process (its stderr goes to /dev/null). Throws
// core::InputError "libfreexl could not read it (...)" naming `path` when the child dies by a
// signal, exits with a non-zero status or sends more than 64 MiB. Public for its test.
std::string answer_of_child(const std::string& path, const std::function<std::string()>& answer);

// The wire format between the two processes, public for its test: `serialize` in the child, `parse`
// in the parent (throws core::InputError naming `path` on a truncated or malformed stream).
std::string serialize_sheets(const std::vector<Sheet>& sheets);
std::string serialize_refusal(int freexl_error);
std::vector<Sheet> parse_sheets(const std::string& bytes, const std::string& path);

// The export in the sheets `Shiftlist` and `Exported Data` (read_eplexor after read_sheets; the
// table's source_sha256 is left to the caller). Public for the fuzz harness of fitlib's side.
EplexorExport eplexor_from_sheets(std::vector<Sheet> sheets, const std::string& path,
                                  const ReadOptions& options = {});

}  // namespace fitlib::data::xls
