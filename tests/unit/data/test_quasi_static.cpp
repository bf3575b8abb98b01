// Quasi-static test tables (docs/formats.md §"Quasi-static tests").
#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/data/quasi_static.hpp"

using namespace fitlib;
using core::DeformationMode;

namespace {

std::string error_of(const std::string& text) {
  try {
    data::parse_quasi_static_table(text, "t.csv");
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(QuasiStaticTable, ReadsEveryModeWithItsOwnColumns) {
  const std::string text =
      "# Treloar-like\n"
      "mode,stretch,shear_strain,volume_ratio,nominal_stress_MPa,pressure_MPa,specimen,temperature_C,strain_rate_per_s\n"
      "uniaxial,2.0,,,0.5,,A,23,0.01\n"
      "equibiaxial,1.5,,,0.4,,A,,\n"
      "pure_shear,1.5,,,0.3,,B,,\n"
      "simple_shear,,0.8,,0.2,,B,,\n"
      "volumetric,,,0.99,,20,C,,\n";
  const auto t = data::parse_quasi_static_table(text, "t.csv");
  ASSERT_EQ(t.rows.size(), 5u);
  EXPECT_EQ(t.rows[0].mode, DeformationMode::uniaxial);
  EXPECT_EQ(t.rows[0].abscissa, 2.0);
  EXPECT_EQ(t.rows[0].temperature_C, 23.0);
  EXPECT_EQ(t.rows[0].strain_rate_per_s, 0.01);
  EXPECT_EQ(t.rows[0].source_line, 3);
  EXPECT_EQ(t.rows[2].mode, DeformationMode::planar);
  EXPECT_EQ(t.rows[3].abscissa, 0.8);
  EXPECT_EQ(t.rows[4].mode, DeformationMode::volumetric);
  EXPECT_EQ(t.rows[4].stress_MPa, 20.0);
  EXPECT_TRUE(std::isnan(t.rows[1].temperature_C));
  EXPECT_TRUE(data::looks_like_quasi_static_csv(text));
  EXPECT_FALSE(data::looks_like_quasi_static_csv("frequency_Hz,storage_MPa,loss_MPa\n1,2,3\n"));
}

TEST(QuasiStaticTable, StrainColumnsSayWhatTheyHold) {
  auto t = data::parse_quasi_static_table("mode,strain,nominal_stress_MPa\nuniaxial,0.5,0.3\nuniaxial,-0.2,-0.4\n", "t");
  EXPECT_DOUBLE_EQ(t.rows[0].abscissa, 1.5);
  EXPECT_DOUBLE_EQ(t.rows[1].abscissa, 0.8);
  t = data::parse_quasi_static_table("mode,strain_percent,nominal_stress_MPa\nplanar,50,0.3\n", "t");
  EXPECT_DOUBLE_EQ(t.rows[0].abscissa, 1.5);
}

TEST(QuasiStaticTable, BadInputNamesFileLineAndColumn) {
  EXPECT_NE(error_of("mode,stretch,nominal_stress_MPa\nuniaxial,nan,0.3\n").find("t.csv:2:2"), std::string::npos);
  EXPECT_NE(error_of("mode,stretch,nominal_stress_MPa\ntorsion,2,0.3\n").find("unknown mode 'torsion'"), std::string::npos);
  EXPECT_NE(error_of("mode,stretch,nominal_stress_MPa\nuniaxial,-1,0.3\n").find("stretch must be > 0"), std::string::npos);
  EXPECT_NE(error_of("mode,strain,nominal_stress_MPa\nuniaxial,-1.5,0.3\n").find("strain gives -0.5"), std::string::npos);
  EXPECT_NE(error_of("mode,stretch,nominal_stress_MPa\nsimple_shear,2,0.3\n").find("shear_strain"), std::string::npos);
  EXPECT_NE(error_of("mode,stretch,stress\nuniaxial,2,0.3\n").find("unknown quasi-static column 'stress'"), std::string::npos);
  EXPECT_NE(error_of("mode,stretch,strain,nominal_stress_MPa\n").find("repeats the stretch"), std::string::npos);
  EXPECT_NE(error_of("mode,stretch,nominal_stress_MPa\n").find("no data rows"), std::string::npos);
  EXPECT_NE(error_of("mode,stretch,nominal_stress_MPa\nuniaxial,2\n").find("row has 2 fields"), std::string::npos);
  EXPECT_NE(error_of("mode,stretch,volume_ratio,nominal_stress_MPa,pressure_MPa\nuniaxial,2,0.9,0.3,\n")
                .find("has a value in 'volume_ratio'"),
            std::string::npos);
  EXPECT_NE(error_of("mode,volume_ratio,pressure_MPa\nvolumetric,0,3\n").find("volume ratio must be > 0"), std::string::npos);
}

TEST(QuasiStaticTable, TheBundledTreloarSetReads) {
  const auto t = data::read_quasi_static_table(std::string(FITLIB_SOURCE_DIR) + "/datasets/materials/treloar1944-czhao.csv");
  int counts[3] = {0, 0, 0};
  for (const auto& r : t.rows) ++counts[static_cast<int>(r.mode)];
  EXPECT_EQ(counts[0], 24);
  EXPECT_EQ(counts[1], 16);
  EXPECT_EQ(counts[2], 13);
}
