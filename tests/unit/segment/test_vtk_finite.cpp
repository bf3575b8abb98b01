// write_vtk refuses a non-finite field before writing (docs/reliability.md, "finite outputs").
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "../../common/temp_path.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/segment/mesh.hpp"

using namespace fitlib::segment;

TEST(SegmentVtk, NaNDisplacementIsRefusedNamingTheNodeAndNothingIsWritten) {
  const Mesh m = build_mesh(CogSection{}, MeshKnobs{});
  VtkFields f;
  f.displacement_mm.assign(m.node_count(), Eigen::Vector2d::Zero());
  const std::string path = fitlib_test::temp_dir() + "nan.vtk";
  write_vtk(m, path, f);
  ASSERT_TRUE(std::filesystem::exists(path));
  std::filesystem::remove(path);
  f.displacement_mm[2].y() = std::numeric_limits<double>::quiet_NaN();
  try {
    write_vtk(m, path, f);
    FAIL() << "NaN written";
  } catch (const fitlib::core::NumericalError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": y displacement of node 3 is not finite");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}
