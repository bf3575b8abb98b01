#include "fitlib/core/json.hpp"

#include "fitlib/core/error.hpp"

namespace fitlib::core {

nlohmann::json parse_json(const std::string& text, const std::string& file_name) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    int line = 1, column = 1;
    for (size_t k = 0; k + 1 < e.byte && k < text.size(); ++k) {
      if (text[k] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw InputError("invalid JSON", file_name, line, column);
  } catch (const nlohmann::json::exception& e) {  // out_of_range: a number literal beyond double
    throw InputError(std::string("invalid JSON: ") + e.what(), file_name);
  }
}

}  // namespace fitlib::core
