// Hyperelastic fit time per model on Treloar's data (datasets/materials/treloar1944-czhao.csv,
// all three modes), with the rms relative error per mode. The baseline of this run is the
// neo-Hooke fit (one linear parameter, one start): each row prints its time as a ratio to it.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "median_time.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/data/quasi_static.hpp"
#include "fitlib/fit/hyperelastic.hpp"

using namespace fitlib;

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  const auto table =
      data::read_quasi_static_table(std::string(FITLIB_SOURCE_DIR) + "/datasets/materials/treloar1944-czhao.csv");
  const std::vector<std::pair<std::string, nlohmann::json>> laws = {
      {"neo-hooke", {}},         {"mooney-rivlin", {{"terms", 2}}}, {"mooney-rivlin", {{"terms", 3}}},
      {"yeoh", {}},              {"reduced-polynomial", {{"terms", 6}}}, {"ogden", {{"terms", 1}}},
      {"ogden", {{"terms", 2}}}, {"ogden", {{"terms", 3}}},         {"ogden", {{"terms", 4}}},
      {"arruda-boyce", {}},      {"gent", {}}};
  const int repeats = quick ? 1 : 5;
  double baseline = 0.0;
  std::printf("%-20s %-12s %6s %10s %8s %8s %8s %8s\n", "model", "options", "starts", "time_ms", "ratio", "UT_%",
              "ET_%", "PS_%");
  for (const auto& [kind, options] : laws) {
    const auto m = model::make_model(kind, options);
    fit::HyperelasticFitResult r;
    std::string refused;
    const double t = median_time(repeats, [&] {
      try {
        r = fit::fit_hyperelastic(table, m);
      } catch (const std::exception& e) {
        refused = e.what();
      }
    });
    if (baseline == 0.0) baseline = t;
    if (!refused.empty()) {
      std::printf("%-20s %-12s refused in %.1f ms: %s\n", kind.c_str(), options.dump().c_str(), 1e3 * t, refused.c_str());
      continue;
    }
    double e[3] = {0, 0, 0};
    for (const auto& f : r.figures) e[static_cast<int>(f.mode)] = 100 * f.rms_rel_error;
    std::printf("%-20s %-12s %6d %10.2f %8.1f %8.2f %8.2f %8.2f\n", kind.c_str(), options.dump().c_str(), r.starts,
                1e3 * t, t / baseline, e[0], e[1], e[2]);
  }
  return 0;
}
