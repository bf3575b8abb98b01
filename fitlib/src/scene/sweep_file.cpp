// Reading and validating a sweep file (docs/sweep.md "Sweep file").
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <set>

#include <boost/algorithm/string/join.hpp>
#include <toml++/toml.h>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/scene/scene_toml.hpp"
#include "fitlib/scene/sweep.hpp"
#include "sweep_case.hpp"

namespace fitlib::scene {
namespace {

using core::InputError;

[[noreturn]] void fail(const std::string& source, const toml::node* at, const std::string& key,
                       const std::string& msg) {
  const auto where = at ? at->source().begin : toml::source_position{};
  throw InputError(msg, source, static_cast<int>(where.line), static_cast<int>(where.column), key);
}

std::string relative_to(const std::string& source, const std::string& p) {
  const std::filesystem::path f(p);
  if (f.is_absolute()) return f.lexically_normal().string();
  return (std::filesystem::path(source).parent_path() / f).lexically_normal().string();
}

// A scalar TOML value and its printed label.
std::pair<SweepValue, std::string> scalar(const toml::node& n, const std::string& source, const std::string& key) {
  if (auto b = n.as_boolean()) return {b->get(), b->get() ? "true" : "false"};
  if (auto i = n.as_integer()) return {i->get(), std::to_string(i->get())};
  if (auto f = n.as_floating_point()) {
    if (!std::isfinite(f->get())) fail(source, &n, key, "expects a finite number");
    return {f->get(), core::format_number(f->get())};
  }
  if (auto s = n.as_string()) return {s->get(), s->get()};
  fail(source, &n, key, "expects a number, string or boolean");
}

void check_keys(const toml::table& t, std::initializer_list<const char*> allowed, const std::string& source,
                const std::string& prefix) {
  for (auto&& [k, v] : t) {
    const std::string key(k.str());
    if (std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; })) continue;
    const std::vector<std::string> known(allowed.begin(), allowed.end());
    fail(source, &v, prefix + key, "unknown key; this table takes " + boost::algorithm::join(known, ", ") + " (docs/sweep.md)");
  }
}

const toml::array& nonempty_array(const toml::table& t, const char* name, const std::string& source,
                                  const std::string& key) {
  const toml::node* n = t.get(name);
  if (!n) fail(source, &t, key, "missing");
  const toml::array* a = n->as_array();
  if (!a || a->empty()) fail(source, n, key, "expects a non-empty array");
  return *a;
}

// [set]: nested tables flatten to dotted key paths ("life.fidelity").
void flatten_set(const toml::table& t, const std::string& prefix, Sweep& s, const std::string& source) {
  for (auto&& [k, v] : t) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (auto sub = v.as_table()) {
      flatten_set(*sub, key, s, source);
      continue;
    }
    auto [value, label] = scalar(v, source, "set." + key);
    s.fixed.push_back({key, {value}, {label}});
  }
}

void parse_scenes(const toml::table& root, Sweep& s, const std::string& source) {
  for (const toml::node& n : nonempty_array(root, "scenes", source, "scenes")) {
    const auto* p = n.as_string();
    if (!p) fail(source, &n, "scenes", "expects file names (strings)");
    s.scene_labels.push_back(p->get());
    s.scenes.push_back(relative_to(source, p->get()));
    if (!std::filesystem::is_regular_file(s.scenes.back()))
      fail(source, &n, "scenes[" + std::to_string(s.scenes.size() - 1) + "]", "no scene file " + s.scenes.back());
  }
}

void parse_axes(const toml::table& root, Sweep& s, const std::string& source) {
  const toml::node* n = root.get("axis");
  if (!n) return;
  const toml::array* arr = n->as_array();
  if (!arr) fail(source, n, "axis", "expects [[axis]] tables");
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string at = "axis[" + std::to_string(i) + "]";
    const toml::table* t = (*arr)[i].as_table();
    if (!t) fail(source, &(*arr)[i], at, "expects a table {key or card, values}");
    check_keys(*t, {"key", "card", "values"}, source, at + ".");
    const auto key = t->get_as<std::string>("key");
    const auto card = t->get_as<std::string>("card");
    if (!key == !card) fail(source, t, at + ".key", "give key = \"a.b.c\" or card = \"<role>\", one of them");
    SweepAxis axis;
    if (key) axis.key = key->get();
    if (card) {
      const std::string role = card->get();
      if (std::find(std::begin(kCardRoles), std::end(kCardRoles), role) == std::end(kCardRoles))
        fail(source, card, at + ".card", "card role must be \"bottom\", \"cushion\" or \"cord\"");
      axis.key = "belt.materials." + role;
    }
    std::size_t j = 0;
    for (const toml::node& v : nonempty_array(*t, "values", source, at + ".values")) {
      const std::string vk = at + ".values[" + std::to_string(j++) + "]";
      auto [value, label] = scalar(v, source, vk);
      if (card) {
        if (!v.is_string()) fail(source, &v, vk, "expects a card file name (string)");
        // Absolute, since the scene resolves card paths against its own folder; the label stays as
        // written, so the table is the same wherever the sweep runs.
        value = std::filesystem::absolute(relative_to(source, label)).lexically_normal().string();
        if (!std::filesystem::is_regular_file(std::get<std::string>(value)))
          fail(source, &v, vk, "no card file " + relative_to(source, label));
      }
      axis.values.push_back(value);
      axis.labels.push_back(label);
    }
    for (const auto& other : s.axes)
      if (other.key == axis.key) fail(source, t, at + ".key", "a second axis on " + axis.key + ": give one axis its values");
    for (const auto& other : s.fixed)
      if (other.key == axis.key) fail(source, t, at + ".key", axis.key + " is set in [set] too: give it in one place");
    s.axes.push_back(std::move(axis));
  }
}

void parse_columns(const toml::table& root, Sweep& s, const std::string& source) {
  const toml::table* out = root.get_as<toml::table>("outputs");
  if (!out) {  // the load cycle's headline figures and the life per mode (docs/sweep.md "Columns")
    s.columns = kDefaultSweepColumns;
    return;
  }
  check_keys(*out, {"columns"}, source, "outputs.");
  std::size_t j = 0;
  for (const toml::node& c : nonempty_array(*out, "columns", source, "outputs.columns")) {
    const std::string key = "outputs.columns[" + std::to_string(j++) + "]";
    const auto* name = c.as_string();
    const auto& known = sweep_column_names();
    if (!name || std::find(known.begin(), known.end(), name->get()) == known.end())
      fail(source, &c, key, "unknown column; known: " + boost::algorithm::join(known, ", "));
    if (std::find(s.columns.begin(), s.columns.end(), name->get()) != s.columns.end())
      fail(source, &c, key, "column listed twice");
    s.columns.push_back(name->get());
  }
}

void check_case_count(const toml::table& root, Sweep& s, const std::string& source) {
  double count = static_cast<double>(s.scenes.size());
  for (const auto& a : s.axes) count *= static_cast<double>(a.values.size());
  if (count > kMaxSweepCases)
    fail(source, root.get("axis"), "axis",
         "the grid has " + core::format_number(count) + " cases, above the work cap " +
             core::format_number(kMaxSweepCases) + " (README, work caps); split the sweep");
  s.case_count = static_cast<std::size_t>(count);
}

// The scene keys that name a card file, read from the scene's folder (scene.cpp card_file).
std::vector<std::string> card_keys() {
  std::vector<std::string> keys;
  for (const char* role : kCardRoles) keys.push_back(std::string("belt.materials.") + role);
  keys.push_back("life.card");
  return keys;
}

// The cards the cases can read: each scene's own (after [set]) or, for a key an axis sets, each of
// the axis's values; resolved against the scene's folder, each once, in the order first met.
std::vector<std::string> card_files(const Sweep& s) {
  std::vector<std::string> files;
  const std::vector<std::string> keys = card_keys();
  auto add = [&](const std::filesystem::path& base, const std::string& value) {
    const std::filesystem::path f(value);
    const std::string path = (f.is_absolute() ? f : base / f).lexically_normal().string();
    if (std::find(files.begin(), files.end(), path) == files.end()) files.push_back(path);
  };
  for (std::size_t i = 0; i < s.scenes.size(); ++i) {
    toml::table root = parse_scene_toml(s.scene_texts[i], s.scenes[i]);
    for (const auto& f : s.fixed) set_key_path(root, f.key, f.values[0]);
    const auto base = std::filesystem::path(s.scenes[i]).parent_path();
    for (const std::string& key : keys) {
      const auto axis = std::find_if(s.axes.begin(), s.axes.end(), [&](const SweepAxis& a) { return a.key == key; });
      if (axis == s.axes.end()) {
        if (auto p = root.at_path(key).value<std::string>()) add(base, *p);
        continue;
      }
      for (const auto& v : axis->values)
        if (const auto* p = std::get_if<std::string>(&v)) add(base, *p);
    }
  }
  return files;
}

// The sweep file, its scenes and the cards they name feed the hash, so a resumed table never mixes
// two inputs. A card's bytes only, no path (the hash is the same wherever the sweep runs); a
// missing card counts too (a case refused for it must not resume once it exists).
void hash_inputs(Sweep& s, const std::string& text) {
  std::string hashes = core::sha256_hex(text);
  for (const auto& f : s.scene_texts) hashes += core::sha256_hex(f);
  s.card_files = card_files(s);
  for (const auto& f : s.card_files)
    hashes += std::filesystem::is_regular_file(f) ? core::sha256_hex(core::read_file(f)) : "missing";
  s.sha256 = core::sha256_hex(hashes);
}

}  // namespace

Sweep parse_sweep(const std::string& text, const std::string& source) {
  const toml::table root = parse_scene_toml(text, source);  // same limits and errors as a scene
  check_keys(root, {"name", "scenes", "set", "axis", "outputs"}, source, "");
  Sweep s;
  s.path = source;
  if (const toml::node* n = root.get("name"); n && !n->is_string()) fail(source, n, "name", "expects a string");
  s.name = root["name"].value_or(std::filesystem::path(source).stem().string());
  parse_scenes(root, s, source);
  if (const toml::node* set = root.get("set")) {
    if (!set->as_table()) fail(source, set, "set", "expects a table of dotted keys and values");
    flatten_set(*set->as_table(), "", s, source);
  }
  parse_axes(root, s, source);
  parse_columns(root, s, source);
  check_case_count(root, s, source);
  for (const auto& f : s.scenes) s.scene_texts.push_back(core::read_file(f));
  validate_sweep_values(s, root);  // first: the [set] keys then fit every scene (card_hashes)
  hash_inputs(s, text);
  check_sweep_cost(s);
  return s;
}

Sweep load_sweep(const std::string& path) { return parse_sweep(core::read_file(path), path); }

}  // namespace fitlib::scene
