#pragma once
// Small output helpers shared by the subcommands: exact number formatting and writing to a file
// (atomically) or to stdout.
#include <string>
#include <vector>

namespace fitcli {

// The invocation as typed (recorded in card provenance).
void set_command_line(int argc, char** argv);
const std::string& command_line();

// Shortest text that reads back as the same double.
std::string exact(double x);

// "a,b,c" of exact().
std::string exact_list(const std::vector<double>& values);

// Writes to `path` atomically, or to stdout when path is empty or "-".
void emit(const std::string& path, const std::string& content);

}  // namespace fitcli
