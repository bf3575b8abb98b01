// fitcli accumulate: Zupancic–Emri strain accumulation map Γ(N, ω) as CSV.
#include <iostream>

#include "commands.hpp"
#include "fitlib/belt/accumulation.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/output_paths.hpp"
#include "fitlib/scene/scene.hpp"
#include "fitlib/core/units.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "path_guard.hpp"

namespace fitcli {

void register_accumulate(CLI::App& app) {
  auto* cmd = app.add_subcommand("accumulate", "Strain accumulation map (Zupancic-Emri) as CSV");
  struct Args {
    std::string card, scene, spectrum, out;
    double tau0 = 1.0, kappa = -1.0, omega_min = 1.0, omega_max = 1e4, limit = -1.0;
    long cycles = 10000;
    int omega_points = 100, cycle_points = 50;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--card", a->card, "Material card file with a retardation spectrum (J_g, L_i, lambda_i; - = stdin)");
  cmd->add_option("--scene", a->scene,
                  "Scene file: kappa = centre distance / driver radius and [accumulation] (- = stdin)");
  cmd->add_option("--spectrum", a->spectrum, "Spectrum shape instead of a card: box|gauss|lorentzian|ramp|wedge");
  // The ranges of the scene's [accumulation] keys (scene.cpp parse_accumulation).
  cmd->add_option("--shear-stress-mpa", a->tau0, "Shear stress amplitude tau0 (MPa)")->check(positive_number());
  cmd->add_option("--kappa", a->kappa, "l/R (default from the scene, else pi)")->check(non_negative_number());
  cmd->add_option("--cycles", a->cycles, "Largest cycle count N")->check(number_in(1, 1e12));
  cmd->add_option("--cycle-points", a->cycle_points, "Number of N values (log-spaced)")
      ->check(number_in(1, fitlib::scene::kMaxAccumulationPoints));
  cmd->add_option("--omega-min", a->omega_min, "Smallest angular velocity (1/s)")->check(positive_number());
  cmd->add_option("--omega-max", a->omega_max, "Largest angular velocity (1/s)")->check(positive_number());
  cmd->add_option("--omega-points", a->omega_points, "Number of angular velocities (log-spaced)")
      ->check(number_in(1, fitlib::scene::kMaxAccumulationPoints));
  cmd->add_option("--strain-limit", a->limit, "Strain limit for the critical angular-velocity area")
      ->check(positive_number());
  cmd->add_option("--out", a->out, "CSV file to write (default or - = stdout)");
  add_json_flag(cmd, a->json, "a summary on stdout (the CSV goes to --out)");
  add_verbosity_flags(cmd);
  cmd->callback([a, cmd] {
    using namespace fitlib;
    claim_output("--out", a->out, a->json);
    if (a->card.empty() == a->spectrum.empty() && a->scene.empty())
      throw core::UsageError("give exactly one of --card or --spectrum (or a --scene with [accumulation])");
    scene::Scene sc;
    scene::AccumulationSpec spec;
    if (!a->scene.empty()) {
      sc = load_scene_input(a->scene);
      fitlib::scene::refuse_outputs_on_inputs(sc, {{"--out", a->out}});
      if (sc.accumulation) spec = *sc.accumulation;
    }
    if (!a->card.empty()) {
      sc.materials["bottom"] = input_path(a->card);
      spec.spectrum = "material:bottom";
    } else if (!a->spectrum.empty()) {
      spec.spectrum = a->spectrum;
    }
    // Options given on the command line override the scene's [accumulation].
    auto given = [cmd](const char* name) { return cmd->count(name) > 0; };
    if (given("--shear-stress-mpa") || a->scene.empty()) spec.shear_stress_MPa = a->tau0;
    if (given("--cycles") || a->scene.empty()) spec.cycles = a->cycles;
    if (given("--cycle-points") || a->scene.empty()) spec.cycle_points = a->cycle_points;
    if (given("--omega-min") || a->scene.empty()) spec.omega_min_rad_s = a->omega_min;
    if (given("--omega-max") || a->scene.empty()) spec.omega_max_rad_s = a->omega_max;
    if (given("--omega-points") || a->scene.empty()) spec.omega_points = a->omega_points;
    if (a->limit > 0) spec.strain_limit = a->limit;
    if (spec.omega_max_rad_s < spec.omega_min_rad_s)
      throw core::UsageError("--omega-max " + exact(spec.omega_max_rad_s) + " is below --omega-min " +
                             exact(spec.omega_min_rad_s) + " (with a scene: its [accumulation] omega range)");
    if (static_cast<double>(spec.cycle_points) * spec.omega_points > scene::kMaxAccumulationWork)
      throw core::UsageError("--cycle-points x --omega-points exceeds the work cap " +
                             exact(scene::kMaxAccumulationWork) + " (README, work caps)");
    double kappa = a->kappa >= 0 ? a->kappa : spec.kappa.value_or(core::kPi);
    if (a->kappa < 0 && !spec.kappa && !a->scene.empty()) kappa = scene::drive_kappa(sc);
    std::string source;
    const auto spectrum = scene::scene_spectrum(sc, spec.spectrum, &source);
    const auto map = scene::accumulation_map(spectrum, spec, kappa);
    const std::string csv = scene::accumulation_csv(map);
    if (!a->json) return emit(a->out, csv);
    if (!a->out.empty()) emit(a->out, csv);
    if (a->json) {
      nlohmann::json j{{"kappa", kappa}, {"spectrum", source}, {"shear_stress_MPa", spec.shear_stress_MPa},
                       {"omega_points", map.omega_rad_s.size()}, {"cycle_points", map.cycles.size()}};
      double mx = 0;
      for (double g : map.gamma) mx = std::max(mx, g);
      j["max_strain"] = mx;
      if (!map.critical_cycles.empty()) {
        nlohmann::json area = nlohmann::json::array();
        for (std::size_t i = 0; i < map.omega_rad_s.size(); ++i)
          if (map.critical_cycles[i] > 0)
            area.push_back({{"omega_rad_s", map.omega_rad_s[i]}, {"critical_cycles", map.critical_cycles[i]}});
        j["critical_area"] = area;
      }
      std::cout << j.dump(2) << "\n";
    }
  });
}

}  // namespace fitcli
