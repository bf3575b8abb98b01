// CalculiX as the independent oracle (issue 11 item 6): the same mesh, element (CPE8R), law
// (St Venant–Kirchhoff under NLGEOM) and boundary conditions; stresses at the monitored points
// agree within 3 % of the largest stress component at each point, for CPE8R and (neo-Hookean)
// for the F-bar element. Runs only when ccx is installed (scripts/install-deps.sh installs it).
#include <array>
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

StaticSetup oracle_setup(ElasticLaw law) {
  StaticSetup setup;
  setup.law = law;
  setup.materials = {IsotropicElastic{20.0, 0.4995}, IsotropicElastic{8.0, 0.4995}};
  setup.mesh.fine_size_mm = 0.6;
  setup.mesh.coarse_size_mm = 2.0;
  setup.solver.stepping.steps = 4;
  setup.stiffness = false;
  return setup;
}

// CalculiX's CPE8R integration-point stresses for `load` on the mesh of `setup` (its law and
// moduli), 4 increments; `mesh` receives that mesh.
StaticSolution calculix_solution(const std::string& name, const StaticSetup& setup, const StaticLoad& load, Mesh* mesh) {
  *mesh = build_mesh(setup.section, setup.mesh);
  const auto bottom = make_elastic(setup.law, setup.materials[0].E_MPa, setup.materials[0].nu);
  const auto cushion = make_elastic(setup.law, setup.materials[1].E_MPa, setup.materials[1].nu);
  const StaticProblem p = static_problem(*mesh, {bottom.get(), cushion.get()}, load, setup.ends);
  const fs::path dir = fs::temp_directory_path() / ("fitlib-ccx-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fitlib::core::write_file_atomically((dir / (name + ".inp")).string(), calculix_deck(p, setup.materials, 4, setup.law));
  const std::string cmd = "cd '" + dir.string() + "' && ccx -i " + name + " > " + name + ".log 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << "ccx failed, see " << dir / (name + ".log");
  StaticSolution out = read_calculix_stresses(fitlib::core::read_file((dir / (name + ".dat")).string()), *mesh);
  fs::remove_all(dir);
  return out;
}

// Our stresses with each of `elements` against CalculiX's CPE8R with the same law.
void compare_with_calculix(const std::string& name, const StaticLoad& load, ElasticLaw law,
                           const std::vector<Integration>& elements) {
  StaticSetup setup = oracle_setup(law);
  std::vector<StaticSolution> ours(elements.size());
  Mesh mesh;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    setup.solver.physics.integration = elements[k];
    run_static_case(setup, load, &ours[k], &mesh);
  }
  Mesh ccx_mesh;
  const StaticSolution theirs = calculix_solution(name, setup, load, &ccx_mesh);
  for (const auto& pt : standard_points(setup.section)) {
    const Eigen::Vector2d X(pt.x_mm, pt.y_mm);
    const Eigen::Matrix2d b = stress_at(mesh, theirs, X, Integration::reduced);
    const double scale = b.cwiseAbs().maxCoeff();
    for (std::size_t k = 0; k < elements.size(); ++k) {
      const Eigen::Matrix2d a = stress_at(mesh, ours[k], X, elements[k]);
      std::printf("%s %s %s: ours sxx %.5f syy %.5f sxy %.5f | ccx sxx %.5f syy %.5f sxy %.5f\n", name.c_str(),
                  to_string(elements[k]), pt.name.c_str(), a(0, 0), a(1, 1), a(0, 1), b(0, 0), b(1, 1), b(0, 1));
      EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 0.03 * scale) << name << " at " << pt.name << ", " << to_string(elements[k]);
    }
  }
}

}  // namespace

TEST(SegmentCalculix, StretchAgreesWithCalculix) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  compare_with_calculix("stretch", {0.02, 0.0, 0.0}, ElasticLaw::st_venant_kirchhoff, {Integration::reduced});
}

TEST(SegmentCalculix, BendTo40mmRadiusAgreesWithCalculix) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  compare_with_calculix("bend40", {0.0, 1.0 / 40.0, 0.0}, ElasticLaw::st_venant_kirchhoff, {Integration::reduced});
}

TEST(SegmentCalculix, BendWithBottomPressureAgreesWithCalculix) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  compare_with_calculix("bend40p", {0.0, 1.0 / 40.0, 0.5}, ElasticLaw::st_venant_kirchhoff, {Integration::reduced});
}

// The F-bar element (docs/segment.md §Element choice) against the same CPE8R oracle, with a
// neo-Hookean law: St Venant–Kirchhoff's volumetric term λ tr E is not a function of J, so under
// F̄ it does not converge at ν = 0.4995 (docs/decisions.md). CPE8R is checked alongside.
TEST(SegmentCalculix, FbarElementAgreesWithCalculixInStretchWithNeoHookeanRubber) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  compare_with_calculix("stretchnh", {0.02, 0.0, 0.0}, ElasticLaw::neo_hookean, {Integration::fbar, Integration::reduced});
}

TEST(SegmentCalculix, FbarElementAgreesWithCalculixInBendingWithPressureAndNeoHookeanRubber) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  compare_with_calculix("bend40pnh", {0.0, 1.0 / 40.0, 0.5}, ElasticLaw::neo_hookean, {Integration::fbar, Integration::reduced});
}

// The cushion through its depth (docs/segment.md §"Mode 2 through the cushion"): with the life
// mesh's single cushion row, both elements' stresses at the same points of the cushion
// (interpolated from their integration points, not the nearest one) agree with each other to 1 %
// of the largest component, and their shear σ12 — what separation sees besides σ11 — agrees within
// 3 % with CalculiX's CPE8R on a mesh with 4 cushion rows, including its fall through the depth
// (σ12 at 0.4 mm is 0.60–0.63 of σ12 at 0.1 mm). Bend to R = 40 mm + 0.5 MPa bottom pressure,
// neo-Hookean; points over the cog flank, where the cushion is sheared. (The oracle's σ11 on its
// thin rows oscillates through the depth, ±0.25 MPa at x = 2.1 mm, so σ11 is compared between the
// elements only.)
TEST(SegmentCalculix, CushionStressOfBothElementsWithOneCushionRowAgreesWithCalculixThroughTheDepth) {
  ASSERT_TRUE(have_ccx()) << "ccx not installed (scripts/install-deps.sh installs calculix-ccx)";
  const StaticLoad load{0.0, 1.0 / 40.0, 0.5};
  StaticSetup oracle = oracle_setup(ElasticLaw::neo_hookean);
  oracle.mesh.cushion_rows = 4;
  Mesh fine;
  const StaticSolution theirs = calculix_solution("cushion4", oracle, load, &fine);
  StaticSetup setup = oracle_setup(ElasticLaw::neo_hookean);
  setup.mesh.cushion_rows = 1;
  std::array<StaticSolution, 2> ours;
  Mesh mesh;
  const std::array<Integration, 2> elements{Integration::reduced, Integration::fbar};
  for (int k = 0; k < 2; ++k) {
    setup.solver.physics.integration = elements[k];
    run_static_case(setup, load, &ours[k], &mesh);
  }
  for (double x : {0.9, 1.5, 2.1}) {
    std::array<double, 2> top_shear{}, ccx_top_shear{};
    for (double depth : {0.1, 0.25, 0.4}) {
      const Eigen::Vector2d X(x, -depth);
      const Eigen::Matrix2d b = stress_at(fine, theirs, X, Integration::reduced);
      const Eigen::Matrix2d a0 = stress_at(mesh, ours[0], X, elements[0]), a1 = stress_at(mesh, ours[1], X, elements[1]);
      const double scale = b.cwiseAbs().maxCoeff();
      EXPECT_LT((a0 - a1).cwiseAbs().maxCoeff(), 0.01 * scale) << "(" << x << ", -" << depth << ")";
      for (int k = 0; k < 2; ++k) {
        const Eigen::Matrix2d a = k == 0 ? a0 : a1;
        std::printf("%s (%.2f, -%.2f): ours s11 %.5f s12 %.5f | ccx 4 rows s11 %.5f s12 %.5f\n", to_string(elements[k]),
                    x, depth, a(1, 1), a(0, 1), b(1, 1), b(0, 1));
        EXPECT_NEAR(a(0, 1), b(0, 1), 0.03 * scale) << to_string(elements[k]) << " (" << x << ", -" << depth << ")";
        if (depth == 0.1) top_shear[k] = a(0, 1), ccx_top_shear[k] = b(0, 1);
        if (depth == 0.4) {
          EXPECT_NEAR(a(0, 1) / top_shear[k], b(0, 1) / ccx_top_shear[k], 0.05) << x;
        }
      }
    }
  }
}
