// libfreexl in a child process (fitlib/src/data/eplexor_cells.hpp): whatever the child does, the
// caller gets the cells or an InputError naming the file, the child is reaped and no fd is left open.
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <string>

#include "../../../fitlib/src/data/eplexor_cells.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/data/eplexor.hpp"

namespace {

using namespace fitlib;
using data::xls::Cell;

int open_fds() {
  int n = 0;
  DIR* d = ::opendir("/proc/self/fd");
  while (::readdir(d)) ++n;
  ::closedir(d);
  return n;
}

bool has_unreaped_child() { return !(::waitpid(-1, nullptr, WNOHANG) < 0 && errno == ECHILD); }

// The InputError message of answer_of_child(path, answer); checks the file, the reaping and the fds.
std::string refusal(const std::function<std::string()>& answer) {
  const int fds = open_fds();
  std::string message;
  try {
    data::xls::parse_sheets(data::xls::answer_of_child("book.xls", answer), "book.xls");
    ADD_FAILURE() << "accepted";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.file(), "book.xls");
    message = e.what();
  }
  EXPECT_FALSE(has_unreaped_child());
  EXPECT_EQ(open_fds(), fds);
  return message;
}

data::xls::Sheet example_sheet() {
  data::xls::Sheet s;
  s.name = "Exported Data", s.rows = 65536, s.columns = 256;  // BIFF8's largest sheet
  s.cells[{0, 0}] = Cell{Cell::Kind::text, 0.0, "f"};
  s.cells[{1, 255}] = Cell{Cell::Kind::text, 0.0, std::string("°C\0x", 4)};
  s.cells[{2, 0}] = Cell{Cell::Kind::real, -1.0 / 3.0, ""};
  s.cells[{65535, 3}] = Cell{Cell::Kind::integer, -2147483648.0, ""};
  return s;
}

TEST(EplexorCells, SheetsComeThroughThePipeExactly) {
  const data::xls::Sheet sent = example_sheet();
  const int fds = open_fds();
  const auto got = data::xls::parse_sheets(
      data::xls::answer_of_child("book.xls", [&] { return data::xls::serialize_sheets({sent, sent}); }), "book.xls");
  EXPECT_FALSE(has_unreaped_child());
  EXPECT_EQ(open_fds(), fds);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[1].name, sent.name);
  EXPECT_EQ(got[1].rows, 65536u);
  EXPECT_EQ(got[1].columns, 256u);
  ASSERT_EQ(got[1].cells.size(), 4u);
  for (const auto& [at, cell] : sent.cells) {
    const Cell& back = got[1].cells.at(at);
    EXPECT_EQ(back.kind, cell.kind);
    EXPECT_EQ(back.text, cell.text);
    EXPECT_EQ(back.number, cell.number);  // bit for bit: 8 bytes as they are
  }
}

TEST(EplexorCells, ChildKilledBySignalIsBadInputNamingTheFile) {
  const auto m = refusal([]() -> std::string {
    ::raise(SIGKILL);
    return {};
  });
  EXPECT_NE(m.find("libfreexl could not read it (its reader process was killed by signal 9)"), std::string::npos) << m;
}

TEST(EplexorCells, ChildFailingWithAStatusIsBadInput) {  // e.g. a sanitizer report in libfreexl
  const auto m = refusal([]() -> std::string { ::_exit(1); });
  EXPECT_NE(m.find("libfreexl could not read it (its reader process failed with status 1)"), std::string::npos) << m;
}

TEST(EplexorCells, TruncatedOrMalformedAnswerIsBadInput) {
  std::string whole = data::xls::serialize_sheets({example_sheet()});
  const auto m = refusal([&] { return whole.substr(0, whole.size() - 1); });  // no end record
  EXPECT_NE(m.find("libfreexl could not read it (its reader process gave a malformed answer)"), std::string::npos) << m;
  EXPECT_NE(refusal([] { return std::string("C"); }).find("malformed"), std::string::npos);  // a cell before any sheet
  EXPECT_NE(refusal([] { return std::string("?Z"); }).find("malformed"), std::string::npos);
}

// Fuzz finding (fuzz_eplexor_sheets, timeout): a sheet claiming 2^32 − 1 columns made the column
// search loop for minutes; dimensions beyond BIFF8's are refused where the answer is read.
TEST(EplexorCells, DimensionsBeyondTheXlsLimitsAreBadInput) {
  for (const auto& [rows, columns] : {std::pair{65537u, 1u}, std::pair{1u, 257u}, std::pair{4294967295u, 4294967295u}}) {
    data::xls::Sheet s = example_sheet();
    s.rows = rows, s.columns = columns;
    try {
      data::xls::parse_sheets(data::xls::serialize_sheets({s}), "book.xls");
      ADD_FAILURE() << rows << " x " << columns << " accepted";
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.file(), "book.xls");
      EXPECT_NE(std::string(e.what()).find("beyond the .xls limits (65536 x 256)"), std::string::npos) << e.what();
    }
  }
}

TEST(EplexorCells, OversizedAnswerIsRefusedAndTheChildKilled) {
  const auto m = refusal([] { return std::string((std::size_t{64} << 20) + 1, 'Z'); });
  EXPECT_NE(m.find("more than 64 MiB"), std::string::npos) << m;
}

TEST(EplexorCells, LibfreexlRefusalKeepsItsErrorCode) {
  const auto m = refusal([] { return data::xls::serialize_refusal(-20); });
  EXPECT_NE(m.find("not a readable .xls workbook (libfreexl error -20)"), std::string::npos) << m;
}

// The fuzz finding (docs/reliability.md §2): libfreexl 1.0.6 overreads a stack buffer in
// freexl_open on this workbook. Without sanitizers it refuses the file (-20); under ASan its child
// dies. Either way: bad input naming the file, and this process unharmed.
TEST(EplexorCells, LibfreexlOverreadWorkbookIsBadInputNamingTheFile) {
  const std::string path = std::string(FITLIB_TEST_DATA_DIR) + "/bad/xls/freexl_iconv_overread.xls";
  try {
    data::read_eplexor(path);
    FAIL() << "accepted";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find("libfreexl"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(has_unreaped_child());
}

}  // namespace

// Fuzz finding (fuzz_eplexor_sheets): "inf °C" as the shift list's Ref.Temp. was read by from_chars
// and accepted as an infinite reference temperature.
TEST(EplexorCells, NonFiniteReferenceTemperatureIsBadInputNamingTheCell) {
  data::xls::Sheet shifts;
  shifts.name = "Shiftlist", shifts.rows = 4, shifts.columns = 2;
  shifts.cells[{0, 0}] = Cell{Cell::Kind::text, 0.0, "Ref.Temp."};
  shifts.cells[{1, 0}] = Cell{Cell::Kind::text, 0.0, "Temp."};
  shifts.cells[{2, 0}] = Cell{Cell::Kind::real, 25.0, ""};
  shifts.cells[{2, 1}] = Cell{Cell::Kind::real, 0.0, ""};
  for (const char* text : {"inf °C", "nan °C", "-infinity"}) {
    shifts.cells[{0, 1}] = Cell{Cell::Kind::text, 0.0, text};
    try {
      data::xls::eplexor_from_sheets({shifts}, "book.xls");
      ADD_FAILURE() << text << " accepted";
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.file(), "book.xls");
      EXPECT_EQ(e.line(), 1);
      EXPECT_NE(std::string(e.what()).find("is not a finite number"), std::string::npos) << e.what();
    }
  }
  shifts.cells.erase({0, 0});  // no Ref.Temp. row at all: the reference stayed NaN
  try {
    data::xls::eplexor_from_sheets({shifts}, "book.xls");
    ADD_FAILURE() << "a shift list without Ref.Temp. accepted";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no 'Ref.Temp.' row"), std::string::npos) << e.what();
  }
}

// Fuzz finding (fuzz_eplexor_sheets, UBSan): an integer cell of 7.3e215 in the answer was cast to
// int when its text was asked for; libfreexl's integer cells are ints, so the answer must say so.
TEST(EplexorCells, IntegerCellBeyondIntIsAMalformedAnswer) {
  for (double x : {7.3436e215, 2147483648.0, 0.5}) {
    data::xls::Sheet s = example_sheet();
    s.cells[{3, 0}] = Cell{Cell::Kind::integer, x, ""};
    try {
      data::xls::parse_sheets(data::xls::serialize_sheets({s}), "book.xls");
      ADD_FAILURE() << x << " accepted";
    } catch (const core::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("malformed"), std::string::npos) << e.what();
    }
  }
}
