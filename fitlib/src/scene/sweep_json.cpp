// The sweep table as one JSON document (fitcli sweep --json).
#include <cstdlib>
#include <sstream>

#include "fitlib/scene/sweep_run.hpp"

namespace fitlib::scene {
namespace {

// A field as JSON: empty → null, a number's text → that number (read back exactly), else text.
nlohmann::json field_json(const std::string& text) {
  if (text.empty()) return nullptr;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  const bool numeric = end == text.c_str() + text.size() && text.find_first_of("0123456789") != std::string::npos &&
                       text.find_first_not_of("0123456789+-.e") == std::string::npos;
  if (!numeric) return text;
  if (text.find_first_of(".e") == std::string::npos && text.size() < 16) return std::stoll(text);
  return x;
}

}  // namespace

nlohmann::json sweep_json(const Sweep& sweep, const std::string& table) {
  const auto header = sweep_header(sweep);
  nlohmann::json rows = nlohmann::json::array();
  std::istringstream in(table);
  std::string line;
  std::getline(in, line);  // comment line
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto fields = split_csv_row(line);
    nlohmann::json row = nlohmann::json::object();
    for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) {
      row[header[i]] = sweep_text_column(header[i]) ? (fields[i].empty() ? nlohmann::json(nullptr) : nlohmann::json(fields[i]))
                                   : field_json(fields[i]);
    }
    rows.push_back(std::move(row));
  }
  return {{"sweep", sweep.name}, {"sha256", sweep.sha256}, {"cases", sweep.case_count},
          {"columns", header}, {"rows", rows}};
}

}  // namespace fitlib::scene
