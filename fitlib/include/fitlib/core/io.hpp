#pragma once
// File output that never leaves a half-written file behind, and content hashing for provenance.
#include <string>

namespace fitlib::core {

// Writes `content` to `path` through a temporary in the same folder and a rename.
void write_file_atomically(const std::string& path, const std::string& content);

// Whole file as bytes; InputError naming the file when it cannot be read.
std::string read_file(const std::string& path);

// Lower-case hex SHA-256 of `bytes`.
std::string sha256_hex(const std::string& bytes);

}  // namespace fitlib::core
