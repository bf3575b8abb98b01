#pragma once
// Output conventions shared by the subcommands (docs/cli.md "Conventions"): results on stdout,
// notes and warnings on stderr (--quiet hides them, --verbose adds some), "-" as a file name
// means stdout, files written atomically, exact number formatting.
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

// Declared only: CLI11 2.1 is header-only and costs every file that includes it ~8 s of compile
// CPU (docs/decisions.md "Build: where the test command's compile time goes"); the files that
// build or read options include <CLI/CLI.hpp> themselves.
namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace fitcli {

// The invocation as typed (recorded in card provenance).
void set_command_line(int argc, char** argv);
const std::string& command_line();

// Shortest text that reads back as the same double.
std::string exact(double x);

// "a,b,c" of exact().
std::string exact_list(const std::vector<double>& values);

// --quiet / --verbose on `cmd` (the same switches on every subcommand and on fitcli itself).
void add_verbosity_flags(CLI::App* cmd);
// Celsius temperatures the commands accept, as scenes do: [−273.15, 1000] °C.
CLI::Validator temperature_c_range();
// Finite numbers > 0, ≥ 0 or in a range; the message names the value ("'abc' is not a number",
// "must be > 0, got 0"; NaN and inf are refused).
CLI::Validator positive_number();
CLI::Validator non_negative_number();
CLI::Validator number_in(double low, double high);  // finite, low ≤ x ≤ high
CLI::Validator poisson_ratio_range();               // [0, 0.5)
// Strains (amplitudes ≥ 0 or mean strains) up to 10 in magnitude: 1000 %, beyond any rubber's
// elongation at break (an amplitude of 1e9 ran and printed stresses of 1e9 MPa).
CLI::Validator strain_amplitude_range();
CLI::Validator mean_strain_range();
// Every number option (type FLOAT) of `app` and its subcommands refuses NaN and inf: CLI11's
// ranges let NaN through, and a NaN option reached results (exit 4) or was read as "unset".
void require_finite_numbers(CLI::App& app);
// A number list with an empty item ("--time-s 1,,2", "20,"): CLI11 dropped the gap silently.
// UsageError naming the option. Run on the raw command line before parsing.
void refuse_empty_list_items(int argc, char** argv);
// --json on `cmd`: one JSON document of `what`, on stdout (nothing else there) unless `what` says
// it goes to --out.
void add_json_flag(CLI::App* cmd, bool& json, const std::string& what);
bool quiet();
bool verbose();

// "fitcli: note: …" and "fitcli: warning: …" on stderr (not with --quiet); detail() only with --verbose.
void note(const std::string& message);
void warning(const std::string& message);
void detail(const std::string& message);

// `text` without its "WARNING: …" lines, each said by warning() instead: warnings go to stderr
// (and --quiet hides them) wherever a library's table holds them (life_text).
std::string without_warnings(const std::string& text);

// Where the human summary of a run goes: stdout, or stderr (as notes) when a "-" output
// already took stdout (then nothing with --quiet).
std::ostream& summary();

// Declares that output `path` of option `option` will be written: "-" takes stdout (a usage
// error with --json, whose document is stdout's); a file path is checked now, before the work.
void claim_output(const std::string& option, const std::string& path, bool json);

// Standard streams the caller closed (`fitcli … >&-`) are reopened before any file is opened:
// stdout and stderr on /dev/full, stdin on /dev/null. Else the first file opened takes fd 1 and
// receives stdout's text; now a write to a closed stdout fails as one to a full disk does.
void guard_standard_streams();

// Flushes and closes stdout; InputError "stdout: cannot write …" (exit 3, as a file that cannot be
// written) when any write to it failed: a full disk, /dev/full, a closed stdout.
void finish_stdout();

// Writes to `path` atomically, or to stdout when path is empty or "-".
void emit(const std::string& path, const std::string& content);

// Runs `write(file)`, the library's writer of a file, on `path`; for "-" on a temporary whose
// bytes then go to stdout.
void emit_with(const std::string& path, const std::function<void(const std::string&)>& write);

// A CSV table (header row, comma separated, no quoting) as JSON rows, numbers as numbers.
nlohmann::json csv_rows_json(const std::string& csv);

}  // namespace fitcli
