#pragma once
// Limits checked on TOML text before toml++ parses it (docs/reliability.md). Debian's toml++ 3.3
// recurses once per nesting level and per dotted-key segment, so `a.a.a…= 1` with 10⁵ segments
// overflows the stack (fixed upstream only in later releases); scenes and schedules are a few kB
// with nesting depth ≤ 3, so generous caps cost real files nothing.
#include <cstddef>
#include <string>

namespace fitlib::core {

constexpr std::size_t kTomlMaxBytes = 1 << 20;  // 1 MiB
constexpr int kTomlMaxNesting = 32;             // [ and { open at once
constexpr int kTomlMaxDottedSegments = 32;      // dots in one dotted key

// InputError naming `source` (and line:column) when `text` exceeds a limit.
void check_toml_limits(const std::string& text, const std::string& source);

}  // namespace fitlib::core
