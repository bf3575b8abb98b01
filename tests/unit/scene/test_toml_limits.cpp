// TOML limits checked before toml++ parses (docs/reliability.md, docs/decisions.md).
#include <gtest/gtest.h>

#include <string>

#include "fitlib/core/error.hpp"
#include "fitlib/core/toml_limits.hpp"

using fitlib::core::check_toml_limits;
using fitlib::core::InputError;

namespace {
int line_of_error(const std::string& text) {
  try {
    check_toml_limits(text, "s.toml");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "s.toml");
    return e.line();
  }
  return 0;
}
std::string dotted(int parts) {
  std::string key = "k";
  for (int i = 1; i < parts; ++i) key += ".k";
  return key + " = 1\n";
}
}  // namespace

TEST(TomlLimits, RealScenesPass) {
  EXPECT_EQ(line_of_error("name = \"a.b.c\" # x.y.z [[[[\n[drive]\npulleys = [ {a = 1.5}, {b = [1, [2]]} ]\n"
                          "s = '''\nmulti [[ line\n'''\n" + dotted(32)),
            0);
}

TEST(TomlLimits, DeepNestingAndLongDottedKeysNameTheirLine) {
  EXPECT_EQ(line_of_error("a = 1\nb = " + std::string(33, '[') + std::string(33, ']') + "\n"), 2);
  EXPECT_EQ(line_of_error("a = 1\n" + dotted(34)), 2);
  // Lines inside strings count; brackets and dots inside strings and comments do not.
  EXPECT_EQ(line_of_error("s = \"\"\"\n" + std::string(40, '[') + "\n\"\"\"\n# " + dotted(40) + dotted(40)), 5);
  EXPECT_EQ(line_of_error("s = \"unterminated\n" + dotted(40)), 2);
}

TEST(TomlLimits, LargeFilesAreRefused) {
  EXPECT_EQ(line_of_error(std::string(fitlib::core::kTomlMaxBytes, '\n')), 0);
  EXPECT_THROW(check_toml_limits(std::string(fitlib::core::kTomlMaxBytes + 1, '\n'), "s.toml"), InputError);
}
