#pragma once
// An enum's names, both ways, from one table: the name of a value (the first listed for it) and
// the value of a name (aliases listed after the primary name), with a UsageError that lists the
// primary names. Each module keeps its table beside the enum's to_string/parse functions; the
// EnumNames unit tests check that every value has a name and that names read back.
#include <cstddef>
#include <string>

#include "fitlib/core/error.hpp"

namespace fitlib::core {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

template <class E, std::size_t N>
const char* enum_name(const EnumName<E> (&names)[N], E value) {
  for (const auto& n : names)
    if (n.value == value) return n.name;
  return "?";
}

// "unknown <what> '<text>' (expected a, b or c)".
template <class E, std::size_t N>
E parse_enum(const EnumName<E> (&names)[N], const std::string& text, const std::string& what) {
  for (const auto& n : names)
    if (text == n.name) return n.value;
  std::string expected;
  std::size_t primaries = 0, listed = 0;
  for (std::size_t i = 0; i < N; ++i) primaries += enum_name(names, names[i].value) == names[i].name;
  for (std::size_t i = 0; i < N; ++i) {
    if (enum_name(names, names[i].value) != names[i].name) continue;  // an alias
    ++listed;
    expected += (listed == 1 ? "" : listed == primaries ? " or " : ", ") + std::string(names[i].name);
  }
  throw UsageError("unknown " + what + " '" + text + "' (expected " + expected + ")");
}

}  // namespace fitlib::core
