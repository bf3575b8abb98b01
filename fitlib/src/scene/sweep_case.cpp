// Grid enumeration and the scene of one case (docs/sweep.md "Cases").
#include "sweep_case.hpp"

#include <stdexcept>

#include "fitlib/core/error.hpp"
#include "fitlib/scene/scene_toml.hpp"

namespace fitlib::scene {
namespace {

// "pulleys[2]" → {"pulleys", 2}; "drive" → {"drive", -1}.
std::pair<std::string, long> segment_of(const std::string& s) {
  const auto open = s.find('[');
  if (open == std::string::npos) return {s, -1};
  if (s.back() != ']' || open == 0)
    throw std::invalid_argument("malformed segment '" + s + "' (expected name or name[index])");
  const std::string digits = s.substr(open + 1, s.size() - open - 2);
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 6)
    throw std::invalid_argument("malformed index in '" + s + "'");
  return {s.substr(0, open), std::stol(digits)};
}

std::vector<std::string> split_dots(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const auto dot = path.find('.', start);
    parts.push_back(path.substr(start, dot - start));
    if (parts.back().empty()) throw std::invalid_argument("empty segment in key path '" + path + "'");
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

toml::node* child(toml::table& t, const std::string& name, long index, bool last) {
  toml::node* n = t.get(name);
  if (index < 0) {
    if (!n && !last) n = &t.insert_or_assign(name, toml::table{}).first->second;
    return n;
  }
  toml::array* a = n ? n->as_array() : nullptr;
  if (!a) throw std::invalid_argument("'" + name + "' is not an array in the scene");
  if (static_cast<std::size_t>(index) >= a->size())
    throw std::invalid_argument("'" + name + "' has " + std::to_string(a->size()) + " elements");
  return a->get(static_cast<std::size_t>(index));
}

void assign(toml::table& t, const std::string& name, long index, const SweepValue& v) {
  auto put = [&](auto&& x) {
    if (index < 0) {
      t.insert_or_assign(name, x);
    } else {
      auto& a = *t.get(name)->as_array();
      a.replace(a.cbegin() + index, x);
    }
  };
  std::visit([&](const auto& x) { put(x); }, v);
}

}  // namespace

void set_key_path(toml::table& root, const std::string& key_path, const SweepValue& value) {
  const auto parts = split_dots(key_path);
  toml::table* t = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const auto [name, index] = segment_of(parts[i]);
    toml::node* n = child(*t, name, index, false);
    t = n ? n->as_table() : nullptr;
    if (!t) throw std::invalid_argument("'" + parts[i] + "' is not a table in the scene");
  }
  const auto [name, index] = segment_of(parts.back());
  toml::node* n = child(*t, name, index, true);
  if (n && (n->is_table() || n->is_array()))
    throw std::invalid_argument("'" + parts.back() + "' is a table or array in the scene, not a value");
  assign(*t, name, index, value);
}

SweepCase sweep_case(const Sweep& sweep, std::size_t index) {
  if (index >= sweep.case_count) throw std::out_of_range("sweep case index beyond the grid");
  SweepCase c;
  c.index = index;
  c.value.resize(sweep.axes.size());
  std::size_t rest = index;
  for (std::size_t a = sweep.axes.size(); a-- > 0;) {
    const std::size_t n = sweep.axes[a].values.size();
    c.value[a] = rest % n;
    rest /= n;
  }
  c.scene = rest;
  return c;
}

Scene case_scene(const Sweep& sweep, const SweepCase& c) {
  const std::string& source = sweep.scenes[c.scene];
  toml::table root = parse_scene_toml(sweep.scene_texts[c.scene], source);
  try {
    for (const auto& f : sweep.fixed) set_key_path(root, f.key, f.values[0]);
    for (std::size_t a = 0; a < sweep.axes.size(); ++a)
      set_key_path(root, sweep.axes[a].key, sweep.axes[a].values[c.value[a]]);
  } catch (const std::invalid_argument& e) {
    throw core::InputError(e.what(), sweep.path, 0, 0, "axis");
  }
  Scene scene = parse_scene_table(root, source);
  scene.segment_thread_cap = 1;  // the sweep's threads and ranks run the cases side by side
  return scene;
}

namespace {

[[noreturn]] void rethrow_at(const Sweep& sweep, const toml::node* at, const std::string& key,
                             const std::string& what) {
  const auto where = at ? at->source().begin : toml::source_position{};
  throw core::InputError("the scene rejects this value: " + what, sweep.path, static_cast<int>(where.line),
                         static_cast<int>(where.column), key);
}

// The scene with every [set] key and, for `axis` ≥ 0, value `value` of that axis alone.
void try_value(const Sweep& sweep, std::size_t scene, long axis, std::size_t value) {
  toml::table root = parse_scene_toml(sweep.scene_texts[scene], sweep.scenes[scene]);
  for (const auto& f : sweep.fixed) set_key_path(root, f.key, f.values[0]);
  if (axis >= 0) set_key_path(root, sweep.axes[axis].key, sweep.axes[axis].values[value]);
  parse_scene_table(root, sweep.scenes[scene]);
}

}  // namespace

void validate_sweep_values(const Sweep& sweep, const toml::table& sweep_root) {
  for (std::size_t s = 0; s < sweep.scenes.size(); ++s) {
    try {
      try_value(sweep, s, -1, 0);
    } catch (const std::invalid_argument& e) {
      rethrow_at(sweep, sweep_root.get("set"), "set", e.what());
    } catch (const core::InputError& e) {
      rethrow_at(sweep, sweep_root.get("scenes"), "scenes[" + std::to_string(s) + "]", e.what());
    }
  }
  const toml::array* axes = sweep_root["axis"].as_array();
  for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
    const toml::array* values = (*axes)[a].as_table()->get_as<toml::array>("values");
    for (std::size_t v = 0; v < sweep.axes[a].values.size(); ++v) {
      const std::string key = "axis[" + std::to_string(a) + "].values[" + std::to_string(v) + "]";
      try {
        try_value(sweep, 0, static_cast<long>(a), v);
      } catch (const std::invalid_argument& e) {
        rethrow_at(sweep, values->get(v), key, sweep.axes[a].key + ": " + e.what());
      } catch (const core::InputError& e) {
        rethrow_at(sweep, values->get(v), key, e.what());
      }
    }
  }
}

}  // namespace fitlib::scene
