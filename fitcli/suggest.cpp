#include "suggest.hpp"

#include <algorithm>

namespace fitcli {
namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = 3;
  for (const auto& c : candidates) {
    const std::size_t d = c.rfind(word, 0) == 0 && !word.empty() ? 1 : edit_distance(word, c);
    if (d < best_distance) best = c, best_distance = d;
  }
  return best;
}

std::string subcommand_hint(int argc, char** argv, const std::vector<std::string>& subcommands) {
  if (argc < 2 || argv[1][0] == '-') return "";
  const std::string word = argv[1];
  if (std::find(subcommands.begin(), subcommands.end(), word) != subcommands.end()) return "";
  const std::string near = nearest_word(word, subcommands);
  return near.empty() ? "'" + word + "' is no subcommand; fitcli --help lists them"
                      : "did you mean '" + near + "'? ('" + word + "' is no subcommand; fitcli --help lists them)";
}

}  // namespace fitcli
