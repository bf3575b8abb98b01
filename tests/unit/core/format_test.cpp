// The one number formatter (core/format.hpp): shortest round trip, %.Ng with field limits,
// independent of the C and C++ locale.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <locale>
#include <random>
#include <sstream>
#include <string>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib {
namespace {

// Doubles over the whole range: random bit patterns (every exponent) and random decimals of a
// few digits (the values people type), without NaN and infinity.
std::vector<double> random_doubles(int count) {
  std::mt19937_64 rng(20260418);
  std::vector<double> v;
  while (static_cast<int>(v.size()) < count) {
    const std::uint64_t bits = rng();
    double x;
    std::memcpy(&x, &bits, sizeof x);
    if (v.size() % 2 == 1) x = std::ldexp(static_cast<double>(rng() % 100000), -static_cast<int>(rng() % 20)) / 3.0;
    if (std::isfinite(x)) v.push_back(x);
  }
  return v;
}

TEST(FormatNumber, ShortestTextReadsBackExactlyForOneHundredThousandDoubles) {
  for (double x : random_doubles(100000)) {
    const std::string text = core::format_number(x);
    ASSERT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
    // Shortest: not longer than printf's %.{p-1}e with the fewest digits p that read back.
    char scientific[40];
    int p = 1;
    for (; p < 17; ++p) {
      std::snprintf(scientific, sizeof scientific, "%.*e", p - 1, x);
      if (std::strtod(scientific, nullptr) == x) break;
    }
    std::snprintf(scientific, sizeof scientific, "%.*e", p - 1, x);
    ASSERT_LE(text.size(), std::strlen(scientific)) << text << " vs " << scientific;
  }
}

TEST(FormatNumber, KnownTexts) {
  EXPECT_EQ(core::format_number(0.1), "0.1");
  EXPECT_EQ(core::format_number(2000.0), "2000");
  EXPECT_EQ(core::format_number(1e6), "1e+06");
  EXPECT_EQ(core::format_number(-0.0), "-0");
  EXPECT_EQ(core::format_number(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(core::format_number(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(core::format_number(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(FormatNumber, SignificantDigitsMatchPrintfAndRespectTheFieldLimit) {
  for (int digits : {1, 6, 10, 13, 17}) {
    for (double x : random_doubles(20000)) {
      const std::string text = core::format_number(x, digits);
      char expected[48];
      std::snprintf(expected, sizeof expected, "%.*g", digits, x);  // the C locale here
      ASSERT_EQ(text, expected) << digits;
      ASSERT_LE(static_cast<int>(text.size()), digits + 7) << text;
      if (std::abs(x) < 1e307)  // (%.1g of 1.5e308 is 2e+308, beyond the range)
        ASSERT_LE(std::abs(std::strtod(text.c_str(), nullptr) - x), std::abs(x) * std::pow(10.0, 1 - digits)) << text;
    }
  }
  EXPECT_EQ(core::format_number(1.0 / 3.0, 10), "0.3333333333");
  EXPECT_LE(core::format_number(-1.2345678901234567e-300, 13).size(), 20u);  // CalculiX's 20 characters
  EXPECT_THROW(core::format_number(1.0, 0), core::UsageError);
  EXPECT_THROW(core::format_number(1.0, 18), core::UsageError);
}

// A decimal-comma locale, built in-process (no installed locale needed): the formatter must not
// follow the global locale, whatever the program (or a host application) set.
struct DecimalComma : std::numpunct<char> {
  char do_decimal_point() const override { return ','; }
};

TEST(FormatNumber, ADecimalCommaLocaleChangesNothing) {
  const auto doubles = random_doubles(2000);
  std::vector<std::string> before;
  for (double x : doubles) before.push_back(core::format_number(x) + " " + core::format_number(x, 10));
  const std::locale previous = std::locale::global(std::locale(std::locale::classic(), new DecimalComma));
  std::ostringstream probe;
  probe << 0.5;
  EXPECT_EQ(probe.str(), "0,5") << "the locale should use a decimal comma";
  for (std::size_t i = 0; i < doubles.size(); ++i)
    EXPECT_EQ(core::format_number(doubles[i]) + " " + core::format_number(doubles[i], 10), before[i]);
  std::locale::global(previous);
}

}  // namespace
}  // namespace fitlib
