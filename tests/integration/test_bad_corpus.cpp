// The malformed-input corpus (tests/data/bad/manifest.tsv, docs/reliability.md): every row runs
// the real fitcli and must exit with its code (no signal), name the location its message must
// name, write no NaN/inf, and (when it fails) leave a pre-existing output file byte for byte as
// it was. Large cases
// (huge files, 30 kB lines, deep nesting, a million columns, megabyte keys) are mutations of a
// stored base file, made here at run time.
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

const std::string kBad = std::string(FITLIB_TEST_DATA_DIR) + "/bad";
const std::string kSentinel = "sentinel: an existing output that a failed run must not touch\n";

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string part; std::getline(ss, part, separator);) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

std::string last_line(const std::string& text) {
  const auto end = text.find_last_not_of('\n');
  const auto start = text.rfind('\n', end);
  return text.substr(start == std::string::npos ? 0 : start + 1, end - (start == std::string::npos ? 0 : start + 1) + 1);
}

// Mutations of a valid base file into the large malformed cases (not stored in the repository).
const std::map<std::string, std::function<std::string(const std::string&)>>& mutations() {
  static const std::map<std::string, std::function<std::string(const std::string&)>> m = {
      {"longline", [](const std::string& b) { return b + std::string(40000, 'x') + "\n"; }},
      {"field30k", [](const std::string& b) { return b + "shear,1," + std::string(30000, '1') + ",0.1\n"; }},
      {"rows200k_then_bad",
       [](const std::string& b) {
         std::string s = b;
         const std::string row = last_line(b) + "\n";
         s.reserve(b.size() + 200000 * row.size() + 32);
         for (int k = 0; k < 200000; ++k) s += row;
         return s + "shear,x,1,0.1\n";
       }},
      {"columns1e6",
       [](const std::string& b) {
         const auto eol = b.find('\n');
         std::string header = b.substr(0, eol);
         header.reserve(header.size() + 4000000);
         for (int k = 0; k < 1000000; ++k) header += ",x_c";
         return header + b.substr(eol);
       }},
      {"comment30k", [](const std::string& b) { return "#" + std::string(30000, 'x') + "\n" + b; }},
      {"nest100k", [](const std::string&) { return std::string(100000, '[') + std::string(100000, ']'); }},
      {"longkey1m", [](const std::string&) { return "{\"" + std::string(1000000, 'k') + "\": 1}"; }},
      {"nest_arrays_10k",
       [](const std::string& b) { return b + "\nx_deep = " + std::string(10000, '[') + std::string(10000, ']') + "\n"; }},
      {"nest_tables_10k",
       [](const std::string& b) {
         std::string s = b + "\nx_deep = ";
         for (int k = 0; k < 10000; ++k) s += "{a=";
         return s + "1" + std::string(10000, '}') + "\n";
       }},
      {"dotted_key_100k",
       [](const std::string& b) {
         std::string key = "x_deep";
         for (int k = 0; k < 100000; ++k) key += ".a";
         return b + "\n" + key + " = 1\n";
       }},
      {"huge_comment_file",
       [](const std::string& b) {
         std::string s;
         const std::string line = "# " + std::string(78, 'c') + "\n";
         for (int k = 0; k < 100000; ++k) s += line;  // 8 MB
         return s + b;
       }},
  };
  return m;
}

struct RunResult {
  int exit_code = -1;  // 128 + signal when killed
  std::string out, err;
};

// Own runner with names unique to this process and row (not cli_runner.hpp's shared counter).
// {stdout_full} in the arguments sends stdout to /dev/full, {stdout_closed} closes it.
RunResult run(std::string args, const std::string& base) {
  std::string to = ">" + base + ".out";
  for (const auto& [token, redirect] : {std::pair<std::string, std::string>{"{stdout_full}", ">/dev/full"},
                                        {"{stdout_closed}", ">&-"}})
    if (const auto at = args.find(token); at != std::string::npos) args.erase(at, token.size()), to = redirect;
  const std::string cmd = "timeout -s KILL 300 " + std::string(FITCLI_EXE) + " " + args + " " + to + " 2>" +
                          base + ".err </dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_bytes(base + ".out");
  r.err = read_bytes(base + ".err");
  return r;
}

bool has_non_finite(const std::string& text) {
  static const std::regex token(R"((^|[^A-Za-z_])[-+]?(nan|inf|infinity)([^A-Za-z_]|$))", std::regex::icase);
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (line.size() < 4096 && std::regex_search(line, token)) return true;
  return false;
}

struct Row {
  int line = 0;
  std::string file, args;
  int expected = 0;
  std::vector<std::string> must;
};

std::vector<Row> manifest() {
  std::ifstream in(kBad + "/manifest.tsv");
  std::vector<Row> rows;
  int number = 0;
  for (std::string text; std::getline(in, text);) {
    ++number;
    if (text.empty() || text[0] == '#') continue;
    const auto f = split(text, '\t');
    if (f.size() != 5) ADD_FAILURE() << "manifest.tsv:" << number << ": " << f.size() << " fields, expected 5";
    if (f.size() == 5 && !f[4].empty() && f[4] != "base")
      ADD_FAILURE() << "manifest.tsv:" << number << ": unknown tag '" << f[4] << "'";
    if (f.size() != 5 || !f[4].empty()) continue;
    Row r;
    r.line = number;
    r.file = f[0];
    r.args = f[1];
    r.expected = std::stoi(f[2]);
    for (const auto& m : split(f[3], '|'))
      if (!m.empty()) r.must.push_back(m);
    rows.push_back(r);
  }
  return rows;
}

// Runs one row; returns what is wrong with the result (empty if it is as expected).
std::string check_row(const Row& r, const std::string& tmp) {
  const std::string id = "row-" + std::to_string(r.line);
  std::string input;
  if (r.file.rfind("gen:", 0) == 0) {
    const auto parts = split(r.file, ':');
    const auto mutation = mutations().find(parts.at(1));
    if (mutation == mutations().end()) return "unknown mutation '" + parts.at(1) + "'";
    input = tmp + "/" + id + "-" + fs::path(parts.at(2)).filename().string();
    write_bytes(input, mutation->second(read_bytes(kBad + "/" + parts.at(2))));
  } else {
    input = kBad + "/" + r.file;
  }
  const std::string out = tmp + "/out-" + std::to_string(r.line) + ".keep";
  write_bytes(out, kSentinel);
  // The same file by other names: through "/./", a symbolic link and a hard link.
  const std::string link = out + ".symlink", hard = out + ".hardlink";
  fs::remove(link), fs::remove(hard);
  fs::create_symlink(out, link);
  fs::create_hard_link(out, hard);
  std::string args = replace_all(r.args, "{out_dotted}", tmp + "/./out-" + std::to_string(r.line) + ".keep");
  args = replace_all(args, "{out_link}", link);
  args = replace_all(args, "{out_hard}", hard);
  args = replace_all(args, "{}", input);
  args = replace_all(args, "{root}", FITLIB_SOURCE_DIR);
  args = replace_all(args, "{out}", out);
  args = replace_all(args, "{nodir}", tmp + "/no-dir-" + std::to_string(r.line));
  args = replace_all(args, "{tmp}", tmp);
  const RunResult result = run(args, tmp + "/" + id);

  std::string problems;
  if (result.exit_code >= 128) problems += " killed by signal " + std::to_string(result.exit_code - 128) + ";";
  if (result.exit_code != r.expected)
    problems += " exit " + std::to_string(result.exit_code) + ", expected " + std::to_string(r.expected) + ";";
  for (const auto& m : r.must)
    if (result.err.find(m) == std::string::npos) problems += " message lacks '" + m + "';";
  // A row expected to succeed (a long comment is still a valid file) replaces {out}; its content
  // must then be finite.
  if (r.expected != 0 && read_bytes(out) != kSentinel) problems += " the existing output " + out + " was changed;";
  if (r.expected == 0 && has_non_finite(read_bytes(out))) problems += " NaN/inf in " + out + ";";
  if (has_non_finite(result.out)) problems += " NaN/inf on stdout;";
  if (!problems.empty()) problems += " stderr: " + result.err.substr(0, 300);
  return problems;
}

TEST(BadCorpus, EveryMalformedInputExitsWithItsCodeNamesTheLocationAndKeepsOutputs) {
  const std::string tmp = ::testing::TempDir() + "bad-corpus-" + std::to_string(::getpid());
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  const auto rows = manifest();
  EXPECT_GE(rows.size(), 150u);
  int passed = 0;
  for (const auto& r : rows) {
    const std::string problems = check_row(r, tmp);
    if (problems.empty()) ++passed;
    else ADD_FAILURE() << "manifest.tsv:" << r.line << " " << r.file << ":" << problems;
  }
  std::printf("[ corpus   ] %zu rows: %d pass\n", rows.size(), passed);
  fs::remove_all(tmp);
}

}  // namespace
