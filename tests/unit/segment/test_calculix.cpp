// CalculiX as the independent oracle (issue 11 item 6): the same mesh, element (CPE8R), law
// (St Venant–Kirchhoff under NLGEOM) and boundary conditions; stresses at the monitored points
// agree within 3 % of the largest stress component at each point, for CPE8R and for the F-bar
// element. Runs only when ccx is installed (scripts/install-deps.sh installs it).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include <gtest/gtest.h>

#include "fitlib/core/io.hpp"
#include "fitlib/segment/calculix.hpp"
#include "fitlib/segment/static_case.hpp"

using namespace fitlib::segment;
namespace fs = std::filesystem;

namespace {

bool have_ccx() { return std::system("command -v ccx > /dev/null 2>&1") == 0; }

void compare_with_calculix(const std::string& name, const StaticLoad& load) {
  StaticSetup setup;
  setup.law = ElasticLaw::st_venant_kirchhoff;
  setup.materials = {IsotropicElastic{20.0, 0.4995}, IsotropicElastic{8.0, 0.4995}};
  setup.mesh.fine_size_mm = 0.6;
  setup.mesh.coarse_size_mm = 2.0;
  setup.solver.steps = 4;
  setup.stiffness = false;
  StaticSolution ours;
  Mesh mesh;
  run_static_case(setup, load, &ours, &mesh);
  // The F-bar element (docs/segment.md §Element choice) against the same CPE8R oracle.
  StaticSetup fbar = setup;
  fbar.solver.integration = Integration::fbar;
  StaticSolution ours_fbar;
  run_static_case(fbar, load, &ours_fbar, nullptr);

  const auto bottom = make_elastic(setup.law, 20.0, 0.4995), cushion = make_elastic(setup.law, 8.0, 0.4995);
  const StaticProblem p = static_problem(mesh, {bottom.get(), cushion.get()}, load, setup.ends);
  const fs::path dir = fs::temp_directory_path() / ("fitlib-ccx-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fitlib::core::write_file_atomically((dir / (name + ".inp")).string(), calculix_deck(p, setup.materials, 4));
  const std::string cmd = "cd '" + dir.string() + "' && ccx -i " + name + " > " + name + ".log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "ccx failed, see " << dir / (name + ".log");
  const StaticSolution theirs = read_calculix_stresses(fitlib::core::read_file((dir / (name + ".dat")).string()), mesh);
  for (const auto& pt : standard_points(setup.section)) {
    const Eigen::Vector2d X(pt.x_mm, pt.y_mm);
    const Eigen::Matrix2d b = stress_at(mesh, theirs, X, Integration::reduced);
    const double scale = b.cwiseAbs().maxCoeff();
    for (const Integration integration : {Integration::reduced, Integration::fbar}) {
      const Eigen::Matrix2d a = stress_at(mesh, integration == Integration::fbar ? ours_fbar : ours, X, integration);
      std::printf("%s %s %s: ours sxx %.5f syy %.5f sxy %.5f | ccx sxx %.5f syy %.5f sxy %.5f\n", name.c_str(),
                  to_string(integration), pt.name.c_str(), a(0, 0), a(1, 1), a(0, 1), b(0, 0), b(1, 1), b(0, 1));
      EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 0.03 * scale) << name << " at " << pt.name << ", " << to_string(integration);
    }
  }
  fs::remove_all(dir);
}

}  // namespace

TEST(SegmentCalculix, StretchAgreesWithCalculix) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  compare_with_calculix("stretch", {0.02, 0.0, 0.0});
}

TEST(SegmentCalculix, BendTo40mmRadiusAgreesWithCalculix) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  compare_with_calculix("bend40", {0.0, 1.0 / 40.0, 0.0});
}

TEST(SegmentCalculix, BendWithBottomPressureAgreesWithCalculix) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  compare_with_calculix("bend40p", {0.0, 1.0 / 40.0, 0.5});
}
