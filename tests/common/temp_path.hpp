#pragma once
// Per-process temporary folder for tests: ctest runs each test in its own process, several at
// once (and other checkouts may run theirs on the same machine), so no two processes may share
// a file name. The folder is removed at exit unless FITLIB_KEEP_TEST_FILES is set.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace fitlib_test {

inline void remove_temp_dir();

// Never destroyed, so the exit handler can still read it.
inline const std::string& temp_dir() {
  static const std::string* dir = [] {
    auto* d = new std::string(::testing::TempDir() + "fitlib-test-" + std::to_string(::getpid()) + "/");
    std::filesystem::create_directories(*d);
    if (!std::getenv("FITLIB_KEEP_TEST_FILES")) std::atexit(remove_temp_dir);
    return d;
  }();
  return *dir;
}

inline void remove_temp_dir() {
  std::error_code ignored;
  std::filesystem::remove_all(temp_dir(), ignored);
}

// A path in this process's temporary folder.
inline std::string temp_path(const std::string& name) { return temp_dir() + name; }

}  // namespace fitlib_test
