#include "fitlib/fit/staged.hpp"

#include <nlohmann/json.hpp>
#include <sstream>
#include <toml++/toml.h>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/json.hpp"
#include "fitlib/core/toml_limits.hpp"

namespace fitlib::fit {

namespace {

std::vector<std::string> string_list(const nlohmann::json& j, const std::string& key,
                                     const std::string& source) {
  std::vector<std::string> out;
  if (!j.is_array()) throw core::InputError("expected a list of names", source, 0, 0, key);
  for (std::size_t k = 0; k < j.size(); ++k) {
    if (!j[k].is_string())
      throw core::InputError("expected a name (string)", source, 0, 0,
                             key + "[" + std::to_string(k) + "]");
    out.push_back(j[k].get<std::string>());
  }
  return out;
}

Schedule schedule_from_json(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object() || !j.contains("stages") || !j["stages"].is_array() || j["stages"].empty())
    throw core::InputError("a schedule needs a non-empty list 'stages'", source, 0, 0, "stages");
  Schedule schedule;
  for (std::size_t s = 0; s < j["stages"].size(); ++s) {
    const auto& js = j["stages"][s];
    const std::string key = "stages[" + std::to_string(s) + "]";
    if (!js.is_object()) throw core::InputError("a stage is a table/object", source, 0, 0, key);
    Stage st;
    st.name = "stage " + std::to_string(s + 1);
    for (const auto& [name, value] : js.items()) {
      const std::string k = key + "." + name;
      if (name == "name" && value.is_string()) st.name = value.get<std::string>();
      else if (name == "free") st.free = string_list(value, k, source);
      else if (name == "lock") st.lock = string_list(value, k, source);
      else if (name == "backend" && value.is_string()) {
        st.backend = value.get<std::string>();
        if (st.backend != "nnls" && st.backend != "ceres" && st.backend != "nlopt")
          throw core::InputError("backend must be nnls, ceres or nlopt", source, 0, 0, k);
      } else if (name == "multistart" && value.is_number_integer() && value.get<int>() > 0)
        st.multistart = value.get<int>();
      else if (name == "max_iterations" && value.is_number_integer() && value.get<int>() > 0)
        st.max_iterations = value.get<int>();
      else
        throw core::InputError("unknown key or wrong type (expected name, free, lock, backend, "
                               "multistart, max_iterations)", source, 0, 0, k);
    }
    schedule.stages.push_back(st);
  }
  return schedule;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Schedule parse_schedule_json(const std::string& text, const std::string& source) {
  return schedule_from_json(core::parse_json(text, source), source);
}

Schedule load_schedule(const std::string& path) {
  const std::string text = core::read_file(path);
  if (!ends_with(path, ".toml")) return parse_schedule_json(text, path);
  core::check_toml_limits(text, path);
  toml::table table;
  try {
    table = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw core::InputError(std::string(e.description()), path,
                           static_cast<int>(e.source().begin.line),
                           static_cast<int>(e.source().begin.column));
  }
  std::ostringstream json;
  json << toml::json_formatter{table};
  return schedule_from_json(core::parse_json(json.str(), path), path);
}

Schedule default_schedule() {
  Stage global;
  global.name = "global start";
  global.backend = "nlopt";
  Stage finish;
  finish.name = "finish";
  finish.backend = "ceres";
  return Schedule{{global, finish}};
}

std::vector<int> select_parameters(const std::vector<core::ParameterSpec>& specs,
                                   const std::vector<std::string>& selectors,
                                   const std::string& key) {
  std::vector<bool> chosen(specs.size(), false);
  for (std::size_t s = 0; s < selectors.size(); ++s) {
    const std::string& sel = selectors[s];
    bool matched = false;
    for (std::size_t i = 0; i < specs.size(); ++i) {
      bool hit;
      if (sel == "*") hit = true;
      else if (sel.rfind("group:", 0) == 0) hit = specs[i].group == sel.substr(6);
      else if (!sel.empty() && sel.back() == '*')
        hit = specs[i].name.rfind(sel.substr(0, sel.size() - 1), 0) == 0;
      else hit = specs[i].name == sel;
      if (hit) chosen[i] = matched = true;
    }
    if (!matched)
      throw core::InputError("'" + sel + "' selects no parameter of the model", {}, 0, 0,
                             key + "[" + std::to_string(s) + "]");
  }
  std::vector<int> out;
  for (std::size_t i = 0; i < specs.size(); ++i)
    if (chosen[i]) out.push_back(static_cast<int>(i));
  return out;
}

}  // namespace fitlib::fit
