#include "fitlib/scene/output_paths.hpp"

#include <filesystem>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"

namespace fitlib::scene {

std::vector<NamedPath> scene_inputs(const Scene& s) {
  std::vector<NamedPath> files;
  std::error_code ec;
  if (!s.path.empty() && std::filesystem::is_regular_file(s.path, ec)) files.emplace_back("scene", s.path);
  for (const auto& [role, path] : s.materials) files.emplace_back("belt.materials." + role, path);
  if (s.life && !s.life->card.empty()) files.emplace_back("life.card", s.life->card);
  return files;
}

std::vector<std::string> folder_outputs(const Scene& s, const std::string& dir) {
  namespace f = folder_file;
  std::vector<std::string> files;
  for (const char* name : {f::load_history, f::accumulation, f::tension_test, f::stress_history, f::life, f::summary})
    files.push_back((std::filesystem::path(dir) / name).string());
  if (!s.life_field_prefix.empty())
    for (std::size_t k = 0; k < s.life_field_at.size(); ++k)
      files.push_back(s.life_field_prefix + "-" + std::to_string(k) + ".vtk");
  return files;
}

void refuse_outputs_on_inputs(const Scene& s, const std::vector<NamedPath>& outputs) {
  const auto inputs = scene_inputs(s);
  for (const auto& [option, path] : outputs) {
    if (path.empty() || path == "-") continue;
    for (const auto& [key, input] : inputs) {
      if (!core::same_file(path, input)) continue;
      const std::string what = key == "scene" ? "is the scene file the run reads (" + input + ")"
                                              : "is the card the scene names at " + key + " (" + input + ")";
      throw core::UsageError(option + " " + path + " " + what + ": the run would replace its own input; write elsewhere");
    }
  }
}

}  // namespace fitlib::scene
