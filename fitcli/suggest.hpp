#pragma once
// "Did you mean" hints for a mistyped word (a subcommand): CLI11 said only "A subcommand is
// required" for `fitcli evl`.
#include <string>
#include <vector>

namespace fitcli {

// The candidate nearest to `word` by edit distance, if at most 2 edits away (or `word` is its
// prefix); "" otherwise.
std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates);

// "did you mean 'eval'? ('evl' is no subcommand; fitcli --help lists them)" when the first
// argument is no subcommand but close to one; "" otherwise.
std::string subcommand_hint(int argc, char** argv, const std::vector<std::string>& subcommands);

}  // namespace fitcli
