#include "inputs.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <iterator>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/eplexor.hpp"
#include "output.hpp"

namespace fitcli {

namespace {

// Never destroyed, so the exit handler can still read it.
std::string& scratch_dir() {
  static std::string* dir = new std::string;
  return *dir;
}

void remove_scratch() {
  std::error_code ignored;
  if (!scratch_dir().empty()) std::filesystem::remove_all(scratch_dir(), ignored);
}

std::string read_stdin() {
  static bool read = false;
  if (read) throw fitlib::core::UsageError("stdin ('-') can be read only once per run");
  read = true;
  std::cin >> std::noskipws;
  return std::string(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
}

std::string stdin_copy() { return scratch_dir().empty() ? std::string() : scratch_dir() + "/stdin"; }

// Two files with one content (a copy) are two tables whose rows count twice: said, not refused.
void warn_same_bytes(const std::vector<std::string>& files, const std::vector<std::string>& sha256) {
  for (std::size_t i = 0; i < sha256.size() && i < files.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (sha256[i] == sha256[j])
        warning(with_stdin_named(files[j]) + " and " + with_stdin_named(files[i]) +
                " hold the same bytes: their rows count twice (give the file once unless that is meant)");
}

}  // namespace

std::string scratch_path(const std::string& stem) {
  static int counter = 0;
  if (scratch_dir().empty()) {
    std::string pattern = (std::filesystem::temp_directory_path() / "fitcli-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw fitlib::core::InputError("cannot create a scratch folder", pattern);
    scratch_dir() = pattern;
    std::atexit(remove_scratch);
  }
  return scratch_dir() + "/" + stem + (stem == "stdin" ? "" : "-" + std::to_string(++counter));
}

std::string input_path(const std::string& path) {
  if (path != "-") return path;
  const std::string bytes = read_stdin();
  const std::string copy = scratch_path("stdin");
  fitlib::core::write_file_atomically(copy, bytes);
  return copy;
}

std::vector<std::string> input_paths(const std::vector<std::string>& paths) {
  std::vector<std::string> out;
  for (const auto& p : paths) out.push_back(input_path(p));
  return out;
}

std::string with_stdin_named(std::string text) {
  const std::string copy = stdin_copy();
  if (copy.empty()) return text;
  for (auto at = text.find(copy); at != std::string::npos; at = text.find(copy, at + 5)) text.replace(at, copy.size(), "stdin");
  return text;
}

fitlib::scene::Scene load_scene_input(const std::string& path) {
  return path == "-" ? fitlib::scene::parse_scene(read_stdin(), "stdin") : fitlib::scene::load_scene(path);
}

fitlib::data::DynamicTestTable read_tables(const std::vector<std::string>& paths, const std::string& format,
                                           const fitlib::data::ReadOptions& read) {
  using namespace fitlib;
  data::DynamicTestTable all;
  for (const auto& path : paths) {
    data::DynamicTestTable one;
    if (format == "eplexor" || data::is_ole_compound_file(core::read_file(path))) {
      auto x = data::read_eplexor(path, read);
      if (x.has_shift_list)
        note(with_stdin_named(path) + ": EPLEXOR master export, Ref.Temp. " + exact(x.shifts.reference_C) +
             " degC, WLF C1 " + exact(x.wlf_C1) + ", C2 " + exact(x.wlf_C2_K) + " K (" +
             std::to_string(x.shifts.factors.size()) + " shifts)");
      one = std::move(x.table);
    } else {
      one = data::read_dynamic_table(path, read);
    }
    all.rows.insert(all.rows.end(), one.rows.begin(), one.rows.end());
    all.source_files.insert(all.source_files.end(), one.source_files.begin(), one.source_files.end());
    all.source_sha256.insert(all.source_sha256.end(), one.source_sha256.begin(), one.source_sha256.end());
    all.warnings.insert(all.warnings.end(), one.warnings.begin(), one.warnings.end());
  }
  warn_same_bytes(all.source_files, all.source_sha256);
  return all;
}

bool is_relaxation_data(const std::vector<std::string>& paths, const std::string& format) {
  return format == "pyvisco" && !paths.empty() &&
         fitlib::data::looks_like_relaxation_csv(fitlib::core::read_file(paths.front()));
}

fitlib::data::RelaxationTable read_relaxation_tables(const std::vector<std::string>& paths) {
  fitlib::data::RelaxationTable table;
  for (const auto& path : paths) {
    auto one = fitlib::data::read_relaxation_table(path);
    table.rows.insert(table.rows.end(), one.rows.begin(), one.rows.end());
    table.source_files.insert(table.source_files.end(), one.source_files.begin(), one.source_files.end());
    table.source_sha256.insert(table.source_sha256.end(), one.source_sha256.begin(), one.source_sha256.end());
  }
  warn_same_bytes(table.source_files, table.source_sha256);
  return table;
}

}  // namespace fitcli
