#pragma once
// Private: the comment block every FE deck starts with (export.cpp).
#include <string>

namespace fitlib::card {

// `text` as comment lines of at most 80 characters (Abaqus reads 256 per line, LS-DYNA's cards 80).
std::string comment_lines(const char* comment, const std::string& text);

}  // namespace fitlib::card
