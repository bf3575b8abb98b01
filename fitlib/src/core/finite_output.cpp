// Finite-output checks of the writers (fitlib/core/finite_output.hpp).
#include "fitlib/core/finite_output.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <vector>

#include "fitlib/core/error.hpp"

namespace fitlib::core {
namespace {

void walk(const nlohmann::json& j, const std::string& path, const std::string& what) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    throw NumericalError(what + ": " + (path.empty() ? "the value" : path) + " is not finite");
  if (j.is_object())
    for (const auto& [key, value] : j.items()) walk(value, path.empty() ? key : path + "." + key, what);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) walk(j[i], path + "[" + std::to_string(i) + "]", what);
}

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  return out;
}

// The spellings iostreams, to_chars and strtod use for NaN and inf.
bool is_non_finite_text(std::string f) {
  std::transform(f.begin(), f.end(), f.begin(), [](unsigned char c) { return std::tolower(c); });
  if (!f.empty() && (f[0] == '-' || f[0] == '+')) f.erase(0, 1);
  return f == "inf" || f == "infinity" || f.rfind("nan", 0) == 0;
}

}  // namespace

void require_finite_json(const nlohmann::json& document, const std::string& what) { walk(document, "", what); }

void require_finite_csv(const std::string& csv, const std::string& what, const std::set<std::string>& text_columns) {
  std::stringstream in(csv);
  std::string line;
  while (std::getline(in, line) && !line.empty() && line[0] == '#') {
  }
  const auto names = fields(line);
  for (int row = 1; std::getline(in, line); ++row) {
    const auto values = fields(line);
    for (std::size_t c = 0; c < values.size(); ++c) {
      const std::string name = c < names.size() ? names[c] : "#" + std::to_string(c + 1);
      if (!text_columns.count(name) && is_non_finite_text(values[c]))
        throw NumericalError(what + ": column '" + name + "', row " + std::to_string(row) + " is not finite");
    }
  }
}

}  // namespace fitlib::core
