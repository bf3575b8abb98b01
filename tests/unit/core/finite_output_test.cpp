// Finite-output checks (core/finite_output.hpp): the last gate before a computed table or JSON
// document is written; each case would pass a NaN/inf through if the check were missing.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>

#include "fitlib/core/error.hpp"
#include "fitlib/core/finite_output.hpp"

namespace fitlib {
namespace {

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const core::NumericalError& e) {
    return e.what();
  }
  return "no NumericalError";
}

TEST(FiniteOutput, JsonNamesTheKeyPathOfTheFirstNonFiniteNumber) {
  nlohmann::json j = {{"scene", "nan"}, {"life", {{"damage", {0.1, 0.2}}}}};
  EXPECT_NO_THROW(core::require_finite_json(j, "life.json"));  // "nan" as text is a label
  j["life"]["damage"][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message_of([&] { core::require_finite_json(j, "life.json"); }),
            "life.json: life.damage[1] is not finite");
  j["life"]["damage"][1] = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(message_of([&] { core::require_finite_json(j, "x"); }), "x: life.damage[1] is not finite");
}

TEST(FiniteOutput, CsvNamesColumnAndRowOfEveryNonFiniteSpelling) {
  for (const std::string bad : {"nan", "-nan", "NaN", "inf", "-inf", "+inf", "Infinity", "nan(0x8)"}) {
    const std::string csv = "# comment\nt_s,F_N\n0,1\n1," + bad + "\n";
    EXPECT_EQ(message_of([&] { core::require_finite_csv(csv, "load_history.csv"); }),
              "load_history.csv: column 'F_N', row 2 is not finite")
        << bad;
  }
}

TEST(FiniteOutput, CsvPassesFiniteNumbersAndSkipsLabelColumns) {
  const std::string csv = "pulley,F_N\ninf,1e308\nnan,-0\n";
  EXPECT_NO_THROW(core::require_finite_csv(csv, "t.csv", {"pulley"}));
  EXPECT_EQ(message_of([&] { core::require_finite_csv(csv, "t.csv"); }), "t.csv: column 'pulley', row 1 is not finite");
}

}  // namespace
}  // namespace fitlib
