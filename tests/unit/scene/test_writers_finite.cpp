// The scene writers refuse a non-finite result before writing any file (docs/reliability.md,
// "finite outputs"): a NaN forced into a result must give a NumericalError naming the file,
// column or key and row, and leave the output folder without any file.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

#include "../../common/temp_path.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/scene/writers.hpp"

namespace fitlib {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string write_error(const scene::SceneResult& r, const std::string& dir) {
  try {
    scene::write_outputs(scene::Scene{}, r, dir, false);
  } catch (const core::NumericalError& e) {
    return e.what();
  }
  return "written";
}

scene::AccumulationMap small_map() {
  scene::AccumulationMap m;
  m.omega_rad_s = {1.0, 2.0};
  m.cycles = {10, 100};
  m.gamma = {0.1, 0.2, 0.3, 0.4};
  return m;
}

TEST(SceneWriters, NaNInACsvRowIsRefusedBeforeAnyFileIsWritten) {
  const std::string dir = fitlib_test::temp_dir() + "writers-csv";
  scene::SceneResult r;
  r.accumulation = small_map();
  EXPECT_EQ(write_error(r, dir), "written");
  std::filesystem::remove_all(dir);
  r.accumulation->gamma[3] = kNaN;
  EXPECT_EQ(write_error(r, dir), "accumulation.csv: column 'accumulated_strain', row 4 is not finite");
  EXPECT_FALSE(std::filesystem::exists(dir + "/accumulation.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/summary.json"));
}

TEST(SceneWriters, InfInTheSummaryIsRefusedNamingTheKey) {
  const std::string dir = fitlib_test::temp_dir() + "writers-json";
  scene::SceneResult r;
  r.stiffness = scene::Stiffness{};
  r.stiffness->EI_Nmm2 = std::numeric_limits<double>::infinity();
  EXPECT_EQ(write_error(r, dir), "summary.json: stiffness.EI_Nmm2 is not finite");
  EXPECT_FALSE(std::filesystem::exists(dir + "/summary.json"));
}

}  // namespace
}  // namespace fitlib
