#include "output.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "inputs.hpp"

namespace fitcli {

namespace {
std::string& invocation() {
  static std::string text;
  return text;
}

struct Verbosity {
  bool quiet = false, verbose = false, stdout_taken = false;
};
Verbosity& verbosity() {
  static Verbosity v;
  return v;
}

// A stream that drops everything (--quiet summaries when stdout is taken).
std::ostream& null_stream() {
  static std::ostringstream sink;
  sink.str("");
  return sink;
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

namespace {

// True when the whole of `text` is a number (inf and nan included), its value in x.
bool parse_number(const std::string& text, double& x) {
  char* end = nullptr;
  x = std::strtod(text.c_str(), &end);
  return !text.empty() && *end == '\0';
}

// A validator of numbers: `accept(x)` for finite x, else "must be <what>, got <text>".
CLI::Validator number_where(std::function<bool(double)> accept, const std::string& what) {
  return CLI::Validator(
      [accept, what](std::string& text) -> std::string {
        double x = 0.0;
        if (!parse_number(text, x)) return "'" + text + "' is not a number";
        if (!std::isfinite(x) || !accept(x)) return "must be " + what + ", got " + text;
        return "";
      },
      what);
}

}  // namespace

CLI::Validator temperature_c_range() {
  return number_where([](double x) { return x >= -273.15 && x <= 1000.0; }, "in [-273.15, 1000] degC");
}
CLI::Validator positive_number() { return number_where([](double x) { return x > 0.0; }, "> 0"); }
CLI::Validator non_negative_number() { return number_where([](double x) { return x >= 0.0; }, ">= 0"); }
CLI::Validator poisson_ratio_range() {
  return number_where([](double x) { return x >= 0.0 && x < 0.5; }, "in [0, 0.5)");
}
CLI::Validator strain_amplitude_range() {
  return number_where([](double x) { return x >= 0.0 && x <= 10.0; },
                      "in [0, 10] (a strain of 1000 %, beyond any rubber's elongation at break)");
}
CLI::Validator mean_strain_range() {
  return number_where([](double x) { return x >= -10.0 && x <= 10.0; },
                      "in [-10, 10] (a strain of 1000 %, beyond any rubber's elongation at break)");
}
CLI::Validator number_in(double low, double high) {
  return number_where([low, high](double x) { return x >= low && x <= high; },
                      "in [" + fitlib::core::short_number(low) + ", " + fitlib::core::short_number(high) + "]");
}

void require_finite_numbers(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& text) -> std::string {
        double x = 0.0;
        if (parse_number(text, x) && !std::isfinite(x)) return "must be a finite number, got " + text;
        return "";  // not a number at all: CLI11's own conversion says so
      },
      "");
  for (CLI::Option* o : app.get_options())
    if (o->get_type_name().rfind("FLOAT", 0) == 0) o->check(finite);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) require_finite_numbers(*sub);
}

void refuse_empty_list_items(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i], option = i > 1 ? argv[i - 1] : "";
    if (const auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos)
      option = arg.substr(0, eq), arg = arg.substr(eq + 1);
    const bool numbers = !arg.empty() && arg.find_first_not_of("0123456789+-.eE,") == std::string::npos;
    if (numbers && arg.find(',') != std::string::npos &&
        (arg.find(",,") != std::string::npos || arg.front() == ',' || arg.back() == ','))
      throw fitlib::core::UsageError((option.rfind("-", 0) == 0 ? option + ": " : std::string()) +
                                     "an empty value in the list '" + arg + "' (two commas in a row, or one at an end)");
  }
}

void add_verbosity_flags(CLI::App* cmd) {
  auto* q = cmd->add_flag("--quiet,-q", verbosity().quiet, "No notes or warnings on stderr (errors only)");
  auto* v = cmd->add_flag("--verbose,-v", verbosity().verbose, "More notes on stderr");
  q->excludes(v);
}

void add_json_flag(CLI::App* cmd, bool& json, const std::string& what) {
  cmd->add_flag("--json", json, "One JSON document: " + what);
}

bool quiet() { return verbosity().quiet; }
bool verbose() { return verbosity().verbose && !verbosity().quiet; }

void note(const std::string& message) {
  if (!quiet()) std::cerr << "fitcli: note: " << message << "\n";
}

void warning(const std::string& message) {
  if (!quiet()) std::cerr << "fitcli: warning: " << message << "\n";
}

void detail(const std::string& message) {
  if (verbose()) std::cerr << "fitcli: note: " << message << "\n";
}

std::string without_warnings(const std::string& text) {
  std::istringstream lines(text);
  std::string kept;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("WARNING: ", 0) == 0) warning(line.substr(9));
    else kept += line + "\n";
  }
  return kept;
}

std::ostream& summary() {
  if (!verbosity().stdout_taken) return std::cout;
  return quiet() ? null_stream() : std::cerr;
}

void claim_output(const std::string& option, const std::string& path, bool json) {
  if (path == "-") {
    if (json) throw fitlib::core::UsageError(option + " - and --json both write stdout: give " + option + " a file");
    if (verbosity().stdout_taken) throw fitlib::core::UsageError(option + " -: stdout is already taken by another output");
    verbosity().stdout_taken = true;
  } else if (!path.empty()) {
    fitlib::core::check_output_path(path);
  }
}

namespace {
bool& stdout_was_closed() {  // fd 1 closed at start: a write fails on /dev/full, but says so
  static bool closed = false;
  return closed;
}
}  // namespace

void guard_standard_streams() {
  const char* devices[] = {"/dev/null", "/dev/full", "/dev/full"};
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    if (fd == 1) stdout_was_closed() = true;
    const int opened = ::open(devices[fd], fd == 0 ? O_RDONLY : O_WRONLY);
    if (opened >= 0 && opened != fd) {  // lower fds were open: move it to its place
      ::dup2(opened, fd);
      ::close(opened);
    }
  }
}

namespace {
int& stdout_errno() {  // the reason of the first failed write of stdout
  static int error = 0;
  return error;
}
void flush_stdout() {
  if (std::cout) {  // else the write that failed set errno just now: keep it
    errno = 0;
    std::cout.flush();
  }
  if (!std::cout && stdout_errno() == 0) stdout_errno() = errno;
}
}  // namespace

void finish_stdout() {
  flush_stdout();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  int error = stdout_errno() != 0 ? stdout_errno() : errno;
  if (std::fclose(stdout) != 0 && !failed) error = errno;
  else if (!failed) return;
  const std::string why = stdout_was_closed() ? std::string(" (stdout is closed)")
                          : error != 0        ? std::string(" (") + std::strerror(error) + ")"
                                              : std::string();
  throw fitlib::core::InputError("cannot write the output" + why + ": the results are lost", "stdout");
}

void emit(const std::string& path, const std::string& content) {
  if (path.empty() || path == "-") {
    std::cout << content;
    flush_stdout();
  } else {
    fitlib::core::write_file_atomically(path, content);
  }
}

void emit_with(const std::string& path, const std::function<void(const std::string&)>& write) {
  if (path != "-") return write(path);
  const std::string tmp = scratch_path("stdout");
  write(tmp);
  emit("-", fitlib::core::read_file(tmp));
  std::remove(tmp.c_str());
}

nlohmann::json csv_rows_json(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::vector<std::string> names;
  auto split = [](const std::string& text) {
    std::vector<std::string> fields;
    std::stringstream s(text);
    std::string f;
    while (std::getline(s, f, ',')) fields.push_back(f);
    if (!text.empty() && text.back() == ',') fields.emplace_back();
    return fields;
  };
  nlohmann::json rows = nlohmann::json::array();
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto fields = split(line);
    if (names.empty()) {
      names = fields;
      continue;
    }
    nlohmann::json row = nlohmann::json::object();
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::string f = k < fields.size() ? fields[k] : "";
      char* stop = nullptr;
      const double v = std::strtod(f.c_str(), &stop);
      if (f.empty()) row[names[k]] = nullptr;
      else if (*stop == '\0' && std::isfinite(v)) row[names[k]] = v;
      else row[names[k]] = f;
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace fitcli
