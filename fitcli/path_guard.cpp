#include "path_guard.hpp"

#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/output_folder.hpp"
#include "fitlib/scene/output_paths.hpp"

namespace fitcli {
namespace {

// The options that name files, by role. A sweep's --out also writes FILE.partial and FILE.lock
// (docs/sweep.md), which collect() adds as outputs of their own.
const std::set<std::string>& output_options() {
  static const std::set<std::string> names = {"--out", "--plot", "--vtk", "--surface-out", "--shifts-out", "--peaks-out"};
  return names;
}
const std::set<std::string>& input_options() {
  static const std::set<std::string> names = {"--data",     "--card",     "--scene",   "--sweep",       "--shifts",
                                              "--schedule", "--observed", "--start",   "--signals",     "--specimen",
                                              "--surface",  "--points",   "--constraints"};
  return names;
}

using Named = std::pair<std::string, std::string>;  // option, path

void collect(const CLI::App& app, std::vector<Named>& inputs, std::vector<Named>& outputs) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->get_lnames().empty()) continue;
    const std::string name = "--" + o->get_lnames().front();
    const bool in = input_options().count(name) > 0, out = output_options().count(name) > 0;
    if (!in && !out && name != "--out-dir") continue;
    for (const std::string& path : o->results()) {
      // `--out ''` (an unset shell variable) wrote to stdout as if --out were not given.
      if (path.empty() && o->count() > 0)
        throw fitlib::core::UsageError(name + " '': an empty path names nothing; give a " +
                                       (name == "--out-dir" ? "folder" : "file") + " name");
      if (path.empty() || path == "-" || (!in && !out)) continue;
      (in ? inputs : outputs).emplace_back(name, path);
      if (out && name == "--out" && app.get_name() == "sweep")  // its unfinished rows and its lock, beside a link's target
        for (const char* suffix : {".partial", ".lock"})
          outputs.emplace_back("--out's file", fitlib::core::resolve_links(path) + suffix);
    }
  }
  for (const CLI::App* sub : app.get_subcommands()) collect(*sub, inputs, outputs);
}

}  // namespace

void refuse_colliding_paths(const CLI::App& app) {
  std::vector<Named> inputs, outputs;
  collect(app, inputs, outputs);
  // One input file given twice to one option (--data d.csv --data ./d.csv): its rows counted twice
  // in a fit (docs/decisions.md "fitcli: an input file given twice to one option is refused").
  for (std::size_t i = 0; i < inputs.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (inputs[i].first == inputs[j].first && fitlib::core::same_file(inputs[i].second, inputs[j].second))
        throw fitlib::core::UsageError(inputs[i].first + " " + inputs[i].second + " is given twice (also as " +
                                       inputs[j].second + "): its rows would count twice; give each file once");
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (const auto& [option, path] : inputs)
      if (fitlib::core::same_file(outputs[i].second, path))
        throw fitlib::core::UsageError(outputs[i].first + " " + outputs[i].second + " is the file " + option +
                                       " reads (" + path + "): the run would replace its own input; write elsewhere");
    for (std::size_t j = 0; j < i; ++j)
      if (fitlib::core::same_file(outputs[i].second, outputs[j].second))
        throw fitlib::core::UsageError(outputs[i].first + " and " + outputs[j].first + " name one file (" +
                                       outputs[i].second + "): one output would replace the other");
  }
}

void refuse_out_dir_collisions(const fitlib::scene::Scene& scene, const std::string& dir,
                               const std::vector<Named>& outputs) {
  const std::vector<std::string> files = fitlib::scene::folder_outputs(scene, dir);
  std::vector<Named> written = {{"--out-dir", dir}};
  for (const std::string& f : files) written.emplace_back("--out-dir's file", f);
  written.insert(written.end(), outputs.begin(), outputs.end());
  fitlib::scene::refuse_outputs_on_inputs(scene, written);
  for (const auto& [option, path] : outputs)
    for (const std::string& f : files)
      if (fitlib::core::same_file(path, f))
        throw fitlib::core::UsageError(option + " " + path + " is the file " +
                                       std::filesystem::path(f).filename().string() + " that --out-dir " + dir +
                                       " receives: one output would replace the other");
  fitlib::core::check_output_dir(dir);
}

}  // namespace fitcli
