// Segment FE benchmark (issue 11; plain main, prints its tables):
// 1. Static bend to R = 40 mm with 1 % strain and 0.3 MPa on the bottom (the example scene,
//    Hencky contract point, ν = 0.4995): time versus elements (mesh refinement) and the scaling
//    exponent; baseline = the coarsest mesh in the same run.
// 2. The light reference drive (elastic materials, coarse mesh, 2 cycles): time versus the steps
//    per cycle, the gap-bottom σ22 range and the lives, relative to the finest step count;
//    baseline = the fewest steps in the same run. `bench_segment DIR` writes DIR/cycle.csv of the
//    finest run (the monitored histories).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/core/timer.hpp"
#include "fitlib/scene/segment_life.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"
#include "fitlib/segment/static_case.hpp"

using namespace fitlib;

namespace {

model::MaterialPointPtr iso(double E, double nu) {
  const model::ModelPtr m = model::make_model("elastic-iso", nlohmann::json::object());
  return model::make_material_point(*m, {E, nu});
}

void static_scaling() {
  std::printf("1. static bend R 40 mm, eps 1 %%, p 0.3 MPa, hencky nu 0.4995 (4 steps asked)\n");
  std::printf("%8s %9s %9s %6s %6s %10s %8s %12s\n", "fine_mm", "elements", "equations", "incr", "iter", "time_s",
              "ratio", "gap_s22_MPa");
  double t0 = 0.0, e0 = 0.0;
  std::vector<std::pair<double, double>> pts;
  for (double fine : {1.0, 0.7, 0.5, 0.4}) {
    segment::StaticSetup setup;
    setup.law = segment::ElasticLaw::hencky;
    setup.materials = {segment::IsotropicElastic{20.0, 0.4995}, segment::IsotropicElastic{8.0, 0.4995}};
    setup.mesh.fine_size_mm = fine;
    setup.mesh.coarse_size_mm = std::max(1.5, 2.5 * fine);
    setup.stiffness = false;
    core::Stopwatch watch;
    const segment::StaticResult r = segment::run_static_case(setup, {0.01, 1.0 / 40.0, 0.3});
    const double t = watch.seconds();
    if (t0 == 0.0) t0 = t, e0 = r.elements;
    pts.emplace_back(std::log(r.elements / e0), std::log(t / t0));
    std::printf("%8.2f %9d %9d %6d %6d %10.3f %8.2f %12.5f\n", fine, r.elements, r.equations, r.increments,
                r.newton_iterations, t, t / t0, r.stresses[0].sigma22_MPa);
  }
  const auto& [x, y] = pts.back();
  std::printf("   scaling: time ~ elements^%.2f (coarsest to finest)\n\n", x > 0 ? y / x : NAN);
}

void cycle_steps(const char* out_dir) {
  const scene::Scene s = scene::load_scene(std::string(FITLIB_SOURCE_DIR) + "/datasets/drives/ref-0500-light.toml");
  const belt::DriveCase drive = scene::make_drive(s, scene::resolve_stiffness(s));
  const belt::LoadCycle cycle = belt::compute_load_cycle(drive);
  std::printf("2. light reference drive, elastic (E 20/8 MPa, nu 0.49), coarse mesh, 2 cycles\n");
  std::printf("%6s %6s %6s %9s %8s %12s %12s %12s\n", "steps", "incr", "iter", "time_s", "ratio", "gap_s22_min",
              "N1_cycles", "N2_cycles");
  double t0 = 0.0;
  const int steps[] = {10, 20, 40, 80, 160};
  for (int k = 0; k < 5; ++k) {
    scene::SegmentLifeSetup setup;
    setup.mesh.fine_size_mm = 1.0, setup.mesh.coarse_size_mm = 2.5, setup.mesh.central_pitches = 1.0;
    setup.mesh.end_pitches = 1.0, setup.mesh.cushion_rows = 1;
    setup.cycle.stepping.steps_per_cycle = steps[k];
    setup.cycle.physics.manufactured_radius_mm = drive.geometry.belt_length_mm / (2.0 * M_PI);
    setup.materials = {iso(20.0, 0.49), iso(8.0, 0.49)};
    setup.temperature_C = s.temperature_C;
    const scene::SegmentLife life = scene::segment_life(cycle, drive, setup, fatigue::default_card());
    if (t0 == 0.0) t0 = life.wall_s;
    double gap_min = 0.0;
    for (const auto& q : life.run.points[0].samples) gap_min = std::min(gap_min, q.s22_MPa);
    std::printf("%6d %6d %6d %9.3f %8.2f %12.4f %12.4g %12.4g\n", steps[k], life.run.increments,
                life.run.newton_iterations, life.wall_s, life.wall_s / t0, gap_min, life.report.modes[0].life_cycles,
                life.report.modes[1].life_cycles);
    if (k == 4 && out_dir) segment::write_cycle_csv(life.run, std::string(out_dir) + "/cycle.csv");
  }
}

}  // namespace

int main(int argc, char** argv) {
  static_scaling();
  cycle_steps(argc > 1 ? argv[1] : nullptr);
  return 0;
}
