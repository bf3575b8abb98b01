#pragma once
// Shared by the libFuzzer harnesses (docs/reliability.md). A reader's own errors
// (core::InputError, NumericalError, UsageError) are the expected answer to bad bytes; anything
// else is a finding and aborts so that libFuzzer keeps the input: a crash or sanitizer report, an
// exception of another type (e.g. a JSON or TOML library error that escaped), or a non-finite
// value the reader accepted.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <string>

#include "fitlib/core/error.hpp"

namespace fitlib::fuzz {

[[noreturn]] void finding(const std::string& what);

// Fails (finding) when a value a reader accepted is NaN or infinite.
inline void require_finite(double value, const std::string& what) {
  if (!std::isfinite(value)) finding("accepted a non-finite " + what);
}

// Writes the input to a file of this process (name ends in `extension`) and returns its path:
// the readers under test take paths, exactly as fitcli calls them.
std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& extension);

// Runs `body`; expected errors are swallowed, anything else is a finding.
template <class Body>
int run_reader(Body&& body) {
  try {
    body();
  } catch (const core::InputError&) {
  } catch (const core::NumericalError&) {
  } catch (const core::UsageError&) {
  } catch (const std::exception& e) {
    finding(std::string("unexpected exception type (not a fitlib error): ") + e.what());
  } catch (...) {
    finding("exception not derived from std::exception");
  }
  return 0;
}

}  // namespace fitlib::fuzz
