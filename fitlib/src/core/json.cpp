#include "fitlib/core/json.hpp"

#include "fitlib/core/file_kind.hpp"

#include <cmath>
#include <vector>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"

namespace fitlib::core {
namespace {

using nlohmann::json;

// Where the parser is: one frame per open object or array (the key or index being read).
struct PathFrame {
  bool is_array = false;
  std::string key;
  std::size_t index = 0;
};

std::string path_of(const std::vector<PathFrame>& frames) {
  std::string path;
  for (const auto& f : frames) {
    if (f.is_array) path += "[" + std::to_string(f.index) + "]";
    else if (!f.key.empty()) path += (path.empty() ? "" : ".") + f.key;
  }
  return path;
}

// nlohmann reports a byte offset; the user wants line and column (1-based).
std::pair<int, int> line_column(const std::string& text, std::size_t byte) {
  int line = 1, column = 1;
  for (std::size_t k = 0; k + 1 < byte && k < text.size(); ++k) {
    if (text[k] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

}  // namespace

json parse_json(const std::string& text, const std::string& source) {
  std::vector<PathFrame> frames;
  const auto next_element = [&] {
    if (!frames.empty() && frames.back().is_array) ++frames.back().index;
  };
  const json::parser_callback_t track = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: frames.push_back({false, {}, 0}); break;
      case json::parse_event_t::array_start: frames.push_back({true, {}, 0}); break;
      case json::parse_event_t::key: frames.back().key = parsed.get<std::string>(); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames.pop_back();
        next_element();
        break;
      case json::parse_event_t::value: next_element(); break;
    }
    return true;
  };
  try {
    return json::parse(text, track);
  } catch (const json::parse_error& e) {
    const auto [line, column] = line_column(text, e.byte);
    throw InputError("invalid JSON" + wrong_kind_hint(text, FileKind::json), source, line, column);
  } catch (const json::out_of_range&) {
    throw InputError("number out of the double range", source, 0, 0, path_of(frames));
  } catch (const json::exception& e) {
    throw InputError("invalid JSON", source, 0, 0, path_of(frames));
  }
}

json load_json(const std::string& path) { return parse_json(read_file(path), path); }

double json_number(const json& value, const std::string& source, const std::string& key) {
  if (!value.is_number()) throw InputError("expected a number", source, 0, 0, key);
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw InputError("expected a finite number", source, 0, 0, key);
  return x;
}

std::string json_string(const json& value, const std::string& source, const std::string& key) {
  if (!value.is_string()) throw InputError("expected a string", source, 0, 0, key);
  return value.get<std::string>();
}

bool json_bool(const json& value, const std::string& source, const std::string& key) {
  if (!value.is_boolean()) throw InputError("expected true or false", source, 0, 0, key);
  return value.get<bool>();
}

long long json_integer(const json& value, long long lo, long long hi, const std::string& source,
                       const std::string& key) {
  const double x = json_number(value, source, key);
  if (x != std::floor(x) || x < static_cast<double>(lo) || x > static_cast<double>(hi))
    throw InputError("expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi),
                     source, 0, 0, key);
  return value.is_number_integer() ? value.get<long long>() : static_cast<long long>(x);
}

}  // namespace fitlib::core
