#include <gtest/gtest.h>

#include "fitlib/core/enum_names.hpp"

namespace {

enum class Colour { red, green, blue };
constexpr fitlib::core::EnumName<Colour> kNames[] = {
    {Colour::red, "red"}, {Colour::green, "green"}, {Colour::blue, "blue"}, {Colour::red, "rouge"}};

}  // namespace

TEST(EnumNames, NamesReadBackAndAliasesParse) {
  for (Colour c : {Colour::red, Colour::green, Colour::blue})
    EXPECT_EQ(fitlib::core::parse_enum(kNames, fitlib::core::enum_name(kNames, c), "colour"), c);
  EXPECT_STREQ(fitlib::core::enum_name(kNames, Colour::red), "red");  // the primary name, not the alias
  EXPECT_EQ(fitlib::core::parse_enum(kNames, "rouge", "colour"), Colour::red);
}

TEST(EnumNames, UnknownNameListsThePrimaryNames) {
  try {
    fitlib::core::parse_enum(kNames, "mauve", "colour");
    FAIL() << "no error";
  } catch (const fitlib::core::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown colour 'mauve' (expected red, green or blue)"), std::string::npos)
        << e.what();
  }
}
