#pragma once
// Errors with context. Exit codes follow the command-line contract (docs/formats.md §6):
// 2 usage, 3 bad input (file, line, column or key named), 4 numerical failure.
#include <stdexcept>
#include <string>

namespace fitlib::core {

enum ExitCode : int { kSuccess = 0, kUsageError = 2, kBadInput = 3, kNumericalFailure = 4 };

// Bad input: names where it is (file, 1-based line and column, or a key path).
class InputError : public std::runtime_error {
 public:
  InputError(std::string message, std::string file = {}, int line = 0, int column = 0,
             std::string key = {});
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& key() const { return key_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string file_, key_, detail_;
  int line_, column_;
};

// A solver failed (no convergence, singular system); the message says what and where.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Misuse of the library or command line (a usage error, exit 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A number for a message: %.6g (std::to_string prints 1e-310 as 0.000000 and 1e200 in full).
std::string short_number(double value);

// `value` if finite, else a NumericalError "<what> is not finite": every computed output passes
// here before it is written, so no NaN or inf ever reaches a file.
double require_finite(double value, const std::string& what);

// Maps an exception to the contract's exit code.
int exit_code_for(const std::exception& e);

}  // namespace fitlib::core
