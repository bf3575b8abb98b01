#include "fitlib/core/format.hpp"

#include <charconv>

#include "fitlib/core/error.hpp"

namespace fitlib::core {

std::string format_number(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string format_number(double value, int max_significant) {
  if (max_significant < 1 || max_significant > 17)
    throw UsageError("format_number: significant digits must be 1 … 17, got " + std::to_string(max_significant));
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, max_significant);
  return std::string(buffer, result.ptr);
}

}  // namespace fitlib::core
