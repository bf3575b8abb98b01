#pragma once
// Checks that a CSV reader refuses `text` with an InputError at file, line, column (and key).
#include <gtest/gtest.h>

#include <string>

#include "fitlib/core/error.hpp"

namespace fitlib::fatigue {

template <typename Parse>
void expect_csv_error(Parse parse, const std::string& text, int line, int column,
                      const std::string& key = "") {
  const std::string file = "table.csv";
  try {
    parse(text, file);
    FAIL() << "accepted: " << text;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.file(), file);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.column(), column) << e.what();
    if (!key.empty()) {
      EXPECT_EQ(e.key(), key) << e.what();
    }
  }
}

}  // namespace fitlib::fatigue
