// Master curve from pyvisco's raw isotherms (freq_user_raw.csv, 21 isotherms × 10 points,
// T_ref = −5 °C): time to build the master curve (free per-isotherm shifts), to fit a Prony
// series to it, and to refine shifts and series together; against pyvisco's published pipeline
// (raw isotherms → shifts, WLF, master, fit, reduction: ≈ 3.3 s, log10-RMS 0.0047 / 0.188 before
// reduction; anchors.md) and against a baseline measured in the same run: the joint WLF + Prony
// staged fit of tests/unit/fit (one WLF law instead of free shifts).
// Plain main; usage: bench_master [repeats=3]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "fitlib/core/io.hpp"
#include "fitlib/core/parameter.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/model/model.hpp"

using namespace fitlib;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kPyviscoPipeline_s = 3.3;  // anchors.md, same machine kind
constexpr double kPyviscoStorageRms = 0.0047, kPyviscoLossRms = 0.188;

// Best wall time of `repeats` runs of `run`.
double best_of(int repeats, const std::function<void()>& run) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    run();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  data::ReadOptions read;
  read.format = data::TableFormat::pyvisco;
  read.has_default_mode = true;
  read.default_mode = model::TestMode::uniaxial;
  const auto raw =
      data::read_dynamic_table(std::string(FITLIB_SOURCE_DIR) + "/datasets/materials/pyvisco-freq-raw.csv", read);
  fit::MasterCurveOptions curve_options;
  curve_options.reference_C = -5.0;

  // Baseline (same run): one WLF law and a 16-term Prony series fitted together, staged.
  const int n = 16;
  const auto wlf_model = model::make_model(
      "prony", {{"terms", n}, {"mode", "uniaxial"}, {"temperature_law", "wlf"}, {"reference_C", -5.0}});
  auto start = wlf_model->initial_parameters(fit::summarize(raw));
  for (int i = 0; i < n; ++i) start[1 + n + i] = std::pow(10.0, -14.0 + 26.0 * i / (n - 1));
  start[core::find_parameter(wlf_model->parameters(), "C1")] = 17.44;
  start[core::find_parameter(wlf_model->parameters(), "C2")] = 51.6;
  const std::string schedule = (std::filesystem::temp_directory_path() / "bench_master_schedule.json").string();
  core::write_file_atomically(schedule, R"({"stages": [
    {"name": "moduli", "free": ["*"], "backend": "nnls"},
    {"name": "shifts", "free": ["group:elastic", "group:viscous", "group:shift"], "backend": "ceres"},
    {"name": "all", "free": ["*"], "backend": "ceres"}]})");
  fit::FitOptions staged;
  staged.backend = fit::Backend::staged;
  staged.schedule_path = schedule;
  fit::FitResult baseline;
  const double baseline_s = best_of(repeats, [&] { baseline = fit::fit(wlf_model, raw, staged, &start); });

  fit::MasterCurve curve;
  const double build_s = best_of(std::max(repeats, 20), [&] { curve = fit::build_master_curve(raw, curve_options); });

  std::printf("bench_master: pyvisco freq_user_raw.csv, %zu rows, %zu isotherms, T_ref = -5 degC, best of %d\n",
              raw.rows.size(), curve.isotherms.size(), repeats);
  std::printf("shifts: log10 a_T %.2f (%.1f degC) ... %.2f (%.1f degC); WLF C1 %.2f C2 %.1f K rms %.2f decades; "
              "Arrhenius %.0f kJ/mol rms %.2f decades\n\n",
              curve.isotherms.front().log10_aT, curve.isotherms.front().temperature_C, curve.isotherms.back().log10_aT,
              curve.isotherms.back().temperature_C, curve.wlf.C1, curve.wlf.C2_K, curve.wlf.rms_decades,
              curve.arrhenius.activation_energy_kJ_mol, curve.arrhenius.rms_decades);
  std::printf("%-58s %10s %9s %9s %10s %10s\n", "case", "wall [s]", "rms E'", "rms E''", "vs pyvisco",
              "vs baseline");
  auto row = [&](const char* name, double seconds, double storage, double loss) {
    std::printf("%-58s %10.4f %9.4f %9.4f %9.0fx %9.2fx\n", name, seconds, storage, loss, kPyviscoPipeline_s / seconds,
                baseline_s / seconds);
  };
  std::printf("%-58s %10.1f %9.4f %9.4f %10s %10s\n", "pyvisco pipeline (published, anchors.md)", kPyviscoPipeline_s,
              kPyviscoStorageRms, kPyviscoLossRms, "1x", "-");
  row("baseline: WLF + 16-term Prony, staged (same run)", baseline_s, baseline.metrics.rms_log10_storage,
      baseline.metrics.rms_log10_loss);
  std::printf("%-58s %10.6f %9s %9s %9.0fx %9.2fx\n", "build master curve (free shifts, E')", build_s, "-", "-",
              kPyviscoPipeline_s / build_s, baseline_s / build_s);

  struct Case {
    const char* name;
    int terms;
    double storage_weight;
    bool refine;
  };
  const Case cases[] = {
      {"master + 20-term Prony, equal weights", 20, 1.0, false},
      {"master + 20-term Prony + joint shift refinement", 20, 1.0, true},
      {"master + 30-term Prony, E' weight 500", 30, 500.0, false},
      {"master + 30-term Prony, E' weight 500, joint refinement", 30, 500.0, true},
  };
  for (const auto& c : cases) {
    const auto prony = model::make_model("prony", {{"terms", c.terms}, {"mode", "uniaxial"}});
    fit::FitOptions o;
    o.storage_weight = c.storage_weight;
    fit::MasterFit r;
    const double s = best_of(repeats, [&] { r = fit::fit_master_curve(prony, raw, curve_options, o, c.refine); });
    const auto& m = c.refine ? r.joint->metrics : r.master.metrics;
    row(c.name, s, m.rms_log10_storage, m.rms_log10_loss);
  }
  std::printf("\nE' weight 500 sits at pyvisco's end of the E'/E'' frontier (the data are not Kramers-Kronig\n"
              "consistent; anchors.md); equal weights sit at the other end. Compare like with like.\n");
  return 0;
}
