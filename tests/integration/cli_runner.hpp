#pragma once
// Runs fitcli as a user would and captures exit code, stdout and stderr.
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "common/temp_path.hpp"

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline CliResult run_fitcli(const std::string& args) {
  static int counter = 0;
  const std::string base = fitlib_test::temp_path("fitcli_run_" + std::to_string(++counter));
  const std::string cmd = std::string(FITCLI_EXE) + " " + args + " >" + base + ".out 2>" + base + ".err";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(base + ".out");
  r.err = slurp(base + ".err");
  return r;
}

inline std::string source_path(const std::string& relative) {
  return std::string(FITLIB_SOURCE_DIR) + "/" + relative;
}

inline std::string temp_file(const std::string& name) { return fitlib_test::temp_path(name); }
