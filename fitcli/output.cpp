#include "output.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"

namespace fitcli {

namespace {
std::string& invocation() {
  static std::string text;
  return text;
}
}  // namespace

void set_command_line(int argc, char** argv) {
  std::string& text = invocation();
  text = "fitcli";
  for (int i = 1; i < argc; ++i) text += std::string(" ") + argv[i];
}

const std::string& command_line() { return invocation(); }

std::string exact(double x) { return fitlib::core::format_number(x); }

std::string exact_list(const std::vector<double>& values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ",") + exact(v);
  return text;
}

void emit(const std::string& path, const std::string& content) {
  if (path.empty() || path == "-") {
    std::cout << content;
    std::cout.flush();
  } else {
    fitlib::core::write_file_atomically(path, content);
  }
}

}  // namespace fitcli
