// A file handed to the wrong reader is named by what it looks like (core/file_kind.hpp).
#include <gtest/gtest.h>

#include "fitlib/core/error.hpp"
#include "fitlib/core/file_kind.hpp"
#include "fitlib/core/json.hpp"

namespace fitlib::core {
namespace {

TEST(FileKind, FirstMeaningfulLineTellsJsonTomlAndCsvApart) {
  EXPECT_EQ(sniff_file_kind("{\n  \"schema\": \"fitlib.card/1\"\n}\n"), FileKind::json);
  EXPECT_EQ(sniff_file_kind("[{\"a\": 1}]"), FileKind::json);
  EXPECT_EQ(sniff_file_kind("\xEF\xBB\xBF\r\n  # a comment\nname = \"drive\"\n[drive]\n"), FileKind::toml);
  EXPECT_EQ(sniff_file_kind("[drive]\ntorque_Nm = 5\n"), FileKind::toml);
  EXPECT_EQ(sniff_file_kind("# fitlib dynamic-test table\nmode,frequency_Hz,storage_MPa\nshear,1,2\n"), FileKind::csv);
  EXPECT_EQ(sniff_file_kind("mode;frequency_Hz\n"), FileKind::unknown);  // a semicolon export: its own hint
  EXPECT_EQ(sniff_file_kind(""), FileKind::unknown);
  EXPECT_EQ(wrong_kind_hint("{}", FileKind::json), "");
  EXPECT_EQ(wrong_kind_hint("a,b\n1,2\n", FileKind::json), "; it looks like a CSV table, not JSON");
}

TEST(FileKind, InvalidJsonSaysWhenTheFileIsATableOrAScene) {
  try {
    parse_json("mode,frequency_Hz,storage_MPa\nshear,1,2\n", "t.csv");
    FAIL() << "a table parsed as JSON";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.csv:1:1: invalid JSON; it looks like a CSV table, not JSON"),
              std::string::npos) << e.what();
  }
  try {
    parse_json("name = \"drive\"\n", "s.toml");
    FAIL() << "a scene parsed as JSON";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("it looks like a TOML file (a scene, a sweep or a schedule)"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace fitlib::core
