#pragma once
// The test vocabulary (fitlib/core/test_condition.hpp) under the model's names, and its parser.
#include <string>

#include "fitlib/core/test_condition.hpp"

namespace fitlib::model {

using core::TestCondition;
using core::TestMode;
using core::test_mode_from_label;
using core::to_string;

// test_mode_from_label, throwing core::UsageError for anything else.
TestMode parse_test_mode(const std::string& text);

}  // namespace fitlib::model
