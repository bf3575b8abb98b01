// No code outside `model` decides by a model's or a parameter's name (docs/model.md, "How a new
// model plugs in"): the names come from the registry, the sources from this repository.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "fitlib/core/error.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib {
namespace {

namespace fs = std::filesystem;

// Every kind and every parameter name the registry hands out (with the structural options that
// add parameters), and the stems of numbered names ("tau_3" → "tau_").
std::set<std::string> registry_names() {
  const std::vector<nlohmann::json> variants = {
      nlohmann::json::object(),
      {{"terms", 2}, {"temperature_law", "wlf"}, {"bulk_modulus", true}},
      {{"terms", 2}, {"temperature_law", "polynomial"}, {"linear_factor", true}},
      {{"terms", 2}, {"temperature_law", "arrhenius"}}};
  std::set<std::string> names;
  for (const auto& kind : model::model_kinds()) {
    names.insert(kind);
    for (const auto& options : variants) {
      model::ModelPtr m;
      try {
        m = model::make_model(kind, options);
      } catch (const core::UsageError&) {
        continue;  // an option this kind does not take
      }
      for (const auto& spec : m->parameters()) {
        names.insert(spec.name);
        const auto stem = spec.name.find_last_not_of("0123456789");
        if (stem + 1 < spec.name.size()) names.insert(spec.name.substr(0, stem + 1));
      }
    }
  }
  return names;
}

// The line without its // comment (a comment may name parameters; only code is checked).
std::string code_of(const std::string& line) {
  bool in_string = false;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    if (line[i] == '"' && (i == 0 || line[i - 1] != '\\')) in_string = !in_string;
    if (!in_string && line[i] == '/' && line[i + 1] == '/') return line.substr(0, i);
  }
  return line;
}

// A comparison with a registry name: ==, != or a prefix/lookup call next to the literal, or a
// comparison of kind() / model_kind.
bool compares_a_name(const std::string& line, const std::set<std::string>& names) {
  static const std::regex kind_compare(R"((kind\(\)|model_kind)\s*(==|!=))");
  static const std::regex literal("\"([^\"\\\\]*)\"");
  const std::string code = code_of(line);
  if (std::regex_search(code, kind_compare)) return true;
  for (auto it = std::sregex_iterator(code.begin(), code.end(), literal); it != std::sregex_iterator(); ++it) {
    if (!names.count((*it)[1].str())) continue;
    const std::string before = code.substr(0, it->position());
    const std::string after = code.substr(it->position() + it->length());
    static const std::regex op_before(R"((==|!=)\s*$|(find_parameter|rfind|find|compare|starts_with|value)\([^()]*$)");
    static const std::regex op_after(R"(^\s*(==|!=))");
    if (std::regex_search(before, op_before) || std::regex_search(after, op_after)) return true;
  }
  return false;
}

std::vector<std::string> offending_lines(const std::set<std::string>& names) {
  const fs::path root = FITLIB_SOURCE_DIR;
  std::vector<fs::path> dirs = {root / "fitcli"};
  for (const char* module : {"fit", "card", "surface", "belt", "segment", "fatigue", "scene"}) {
    dirs.push_back(root / "fitlib/src" / module);
    dirs.push_back(root / "fitlib/include/fitlib" / module);
  }
  std::vector<std::string> hits;
  for (const auto& dir : dirs) {
    if (!fs::exists(dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".hpp") continue;
      std::ifstream in(entry.path());
      std::string line;
      for (int n = 1; std::getline(in, line); ++n)
        if (compares_a_name(line, names))
          hits.push_back(fs::relative(entry.path(), root).string() + ":" + std::to_string(n) + ": " + line);
    }
  }
  return hits;
}

TEST(ModelNames, TheRegistryGivesKindsParametersAndStems) {
  const auto names = registry_names();
  for (const char* n : {"prony", "fritzson", "zener3", "C1", "C2", "K", "G_inf", "tau_", "J_g", "L_", "lambda_"})
    EXPECT_TRUE(names.count(n)) << n;
}

TEST(ModelNames, TheScannerFlagsComparisonsAndPassesOtherUses) {
  const auto names = registry_names();
  EXPECT_TRUE(compares_a_name(R"(    if (name == "C2" || x) c2 = i;)", names));
  EXPECT_TRUE(compares_a_name(R"(  if ("prony" != kind) return;)", names));
  EXPECT_TRUE(compares_a_name(R"(  const int i = core::find_parameter(specs, "G_inf");)", names));
  EXPECT_TRUE(compares_a_name(R"(  if (s.rfind("tau_", 0) == 0) ++n;)", names));
  EXPECT_TRUE(compares_a_name(R"(  const double c1 = law.value("C1", 0.0);)", names));
  EXPECT_TRUE(compares_a_name(R"(  if (card.model_kind != other) throw;)", names));
  EXPECT_FALSE(compares_a_name(R"(  // the pole T_ref - C2: name == "C2" was the old way)", names));
  EXPECT_FALSE(compares_a_name(R"(  for (const char* unit : {"Hz", "C", "K", "Pa"}) use(unit);)", names));
  EXPECT_FALSE(compares_a_name(R"(  std::string s = "C2 == C1";)", names));
}

TEST(ModelNames, NoCodeOutsideModelComparesAModelOrParameterName) {
  const auto hits = offending_lines(registry_names());
  std::string listing;
  for (const auto& h : hits) listing += h + "\n";
  EXPECT_TRUE(hits.empty()) << "ask the model's capabilities (model.hpp) instead:\n" << listing;
}

}  // namespace
}  // namespace fitlib
