#include "fitlib/core/error.hpp"

#include <cmath>
#include <cstdio>

namespace fitlib::core {
namespace {
std::string locate(const std::string& message, const std::string& file, int line, int column,
                   const std::string& key) {
  std::string where = file;
  if (line > 0) where += ":" + std::to_string(line);
  if (line > 0 && column > 0) where += ":" + std::to_string(column);
  if (!key.empty()) where += (where.empty() ? "" : ": ") + std::string("key '") + key + "'";
  return where.empty() ? message : where + ": " + message;
}
}  // namespace

InputError::InputError(std::string message, std::string file, int line, int column,
                       std::string key)
    : std::runtime_error(locate(message, file, line, column, key)),
      file_(std::move(file)),
      key_(std::move(key)),
      detail_(std::move(message)),
      line_(line),
      column_(column) {}

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

double require_finite(double value, const std::string& what) {
  if (!std::isfinite(value)) throw NumericalError(what + " is not finite");
  return value;
}

int exit_code_for(const std::exception& e) {
  if (dynamic_cast<const InputError*>(&e)) return kBadInput;
  if (dynamic_cast<const NumericalError*>(&e)) return kNumericalFailure;
  if (dynamic_cast<const UsageError*>(&e)) return kUsageError;
  return kNumericalFailure;
}

}  // namespace fitlib::core
