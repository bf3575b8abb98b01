// pyvisco's inputs: EPLEXOR .xls exports, shift-factor files and relaxation tables
// (docs/data.md §3–5). Data copied into datasets/materials/ (provenance in datasets/README.md).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/eplexor.hpp"
#include "fitlib/data/relaxation.hpp"
#include "fitlib/data/shift_factors.hpp"
#include "fitlib/data/table.hpp"

namespace {

using namespace fitlib;

std::string dataset(const std::string& name) { return std::string(FITLIB_SOURCE_DIR) + "/datasets/materials/" + name; }

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

TEST(Eplexor, RawExportGivesTheRowsOfPyviscosCsv) {
  const auto xls = data::read_eplexor(dataset("pyvisco-eplexor-raw.xls"));
  data::ReadOptions csv_options;
  csv_options.format = data::TableFormat::pyvisco;
  const auto csv = data::read_dynamic_table(dataset("pyvisco-freq-raw.csv"), csv_options);
  ASSERT_EQ(xls.table.rows.size(), 210u);
  ASSERT_EQ(csv.rows.size(), 210u);
  EXPECT_FALSE(xls.has_shift_list);
  // The CSV holds the moduli to 6 decimals (MPa): its rounding is up to 0.5e-6 / 1160 MPa = 4.3e-10
  // relative (external/README says 4e-10; measured max 4.34e-10).
  for (std::size_t i = 0; i < 210; ++i) {
    const auto& a = xls.table.rows[i];
    const auto& b = csv.rows[i];
    SCOPED_TRACE("row " + std::to_string(i));
    EXPECT_EQ(a.condition.mode, core::TestMode::uniaxial);
    EXPECT_LE(relative(a.condition.frequency_Hz, b.condition.frequency_Hz), 5e-10);
    EXPECT_LE(relative(a.condition.temperature_C, b.condition.temperature_C), 5e-10);
    EXPECT_LE(relative(a.storage_MPa, b.storage_MPa), 5e-10);
    EXPECT_LE(relative(a.loss_MPa, b.loss_MPa), 5e-10);
    EXPECT_EQ(a.set, b.set);  // isotherm index from the frequency restarts
    EXPECT_EQ(a.source_line, static_cast<int>(i) + 3);
  }
  EXPECT_EQ(xls.table.source_sha256.size(), 1u);
}

TEST(Eplexor, MasterExportReadsModeAndShiftList) {
  const auto x = data::read_eplexor(dataset("pyvisco-eplexor-master.xls"));
  ASSERT_EQ(x.table.rows.size(), 210u);
  EXPECT_EQ(x.table.rows.front().condition.mode, core::TestMode::uniaxial);
  EXPECT_DOUBLE_EQ(x.table.rows.front().condition.frequency_Hz, 8.3176377110270465e-06);
  EXPECT_DOUBLE_EQ(x.table.rows.front().storage_MPa, 82.391631190160041);
  EXPECT_TRUE(x.table.rows.front().set.empty());
  ASSERT_TRUE(x.has_shift_list);
  EXPECT_EQ(x.shifts.reference_C, 25.0);
  EXPECT_EQ(x.wlf_C1, 13.5);
  EXPECT_EQ(x.wlf_C2_K, 141.19);
  ASSERT_EQ(x.shifts.factors.size(), 21u);
  EXPECT_DOUBLE_EQ(x.shifts.factors.front().temperature_C, 99.963489999999993);
  EXPECT_DOUBLE_EQ(x.shifts.factors.front().log10_aT, -4.0799999999999823);
}

TEST(Eplexor, ShearMasterExport) {
  const auto x = data::read_eplexor(dataset("pyvisco-eplexor-master-shear.xls"));
  ASSERT_EQ(x.table.rows.size(), 183u);
  for (const auto& r : x.table.rows) EXPECT_EQ(r.condition.mode, core::TestMode::shear);
  EXPECT_DOUBLE_EQ(x.table.rows.front().storage_MPa, 0.94613442786072244);
  EXPECT_DOUBLE_EQ(x.table.rows.front().loss_MPa, 0.076453927860698698);
  ASSERT_TRUE(x.has_shift_list);
  EXPECT_EQ(x.shifts.reference_C, -30.0);
  EXPECT_EQ(x.wlf_C1, 727.24);
  EXPECT_EQ(x.wlf_C2_K, 2299.5);
  EXPECT_DOUBLE_EQ(x.shifts.factors.front().log10_aT, -31.319999999999983);
}

TEST(Eplexor, BadCellNamesFileSheetRowAndColumn) {
  const std::string path = std::string(FITLIB_TEST_DATA_DIR) + "/eplexor/negative_storage.xls";
  try {
    data::read_eplexor(path);
    FAIL() << "accepted a negative storage modulus";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), 4);     // spreadsheet row
    EXPECT_EQ(e.column(), 13);  // column M
    EXPECT_NE(std::string(e.what()).find("sheet 'Exported Data', column M 'E''"), std::string::npos) << e.what();
  }
  data::ReadOptions skip;
  skip.skip_bad_rows = true;
  const auto x = data::read_eplexor(path, skip);
  EXPECT_EQ(x.table.rows.size(), 209u);
  ASSERT_EQ(x.table.warnings.size(), 1u);
}

TEST(Eplexor, TextFileIsNotAWorkbook) {
  EXPECT_FALSE(data::is_ole_compound_file(core::read_file(dataset("pyvisco-freq-raw.csv"))));
  EXPECT_TRUE(data::is_ole_compound_file(core::read_file(dataset("pyvisco-eplexor-raw.xls"))));
  EXPECT_THROW(data::read_eplexor(dataset("pyvisco-freq-raw.csv")), core::InputError);
}

TEST(ShiftFactors, ReadsPyviscoFilesWithAndWithoutBom) {
  const auto time = data::read_shift_factors(dataset("pyvisco-time-raw-shift-factors.csv"));
  ASSERT_EQ(time.factors.size(), 21u);
  EXPECT_EQ(time.reference_C, 3.0);
  EXPECT_EQ(time.factors.front().temperature_C, 100.0);
  EXPECT_EQ(time.factors.front().log10_aT, -16.228168239944775);
  const auto freq = data::read_shift_factors(dataset("pyvisco-freq-master-shift-factors.csv"));  // BOM
  ASSERT_EQ(freq.factors.size(), 21u);
  EXPECT_EQ(freq.reference_C, -5.0);
  EXPECT_EQ(freq.factors.front().log10_aT, -11.7);
}

TEST(ShiftFactors, WrittenInPyviscosFormatAndReadBackBitExact) {
  data::ShiftFactorTable t;
  t.factors = {{-49.9612, 7.123456789012345}, {0.1, 0.0}, {100.0, -1.0 / 3.0}};
  const std::string text = data::format_shift_factors(t);
  EXPECT_EQ(text.substr(0, 14), "T,log_aT\nC,-\n-");
  const auto back = data::parse_shift_factors(text, "mem.csv");
  ASSERT_EQ(back.factors.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(back.factors[i].temperature_C, t.factors[i].temperature_C);
    EXPECT_EQ(back.factors[i].log10_aT, t.factors[i].log10_aT);
  }
  EXPECT_EQ(back.reference_C, 0.1);
}

TEST(ShiftFactors, InterpolatesLinearlyAndRefusesFarOutside) {
  data::ShiftFactorTable t;
  t.source_file = "s.csv";
  t.factors = {{20.0, 1.0}, {0.0, 3.0}, {40.0, -2.0}};
  EXPECT_DOUBLE_EQ(data::interpolate_log10_aT(t, 10.0), 2.0);
  EXPECT_DOUBLE_EQ(data::interpolate_log10_aT(t, 30.0), -0.5);
  EXPECT_DOUBLE_EQ(data::interpolate_log10_aT(t, 40.3), -2.0);  // within the 0.5 degC tolerance
  EXPECT_THROW(data::interpolate_log10_aT(t, 41.0), core::InputError);
}

TEST(ShiftFactors, ErrorsNameLineAndColumn) {
  try {
    data::parse_shift_factors("T,log_aT\nC,-\n10,abc\n", "bad.csv");
    FAIL();
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.column(), 2);
  }
  try {
    data::parse_shift_factors("T,log_aT\nF,-\n10,1\n", "bad.csv");
    FAIL();
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.column(), 1);
  }
}

TEST(Relaxation, ReadsPyviscoMasterAndRawIsotherms) {
  const auto master = data::read_relaxation_table(dataset("pyvisco-time-master.csv"));
  ASSERT_EQ(master.rows.size(), 481u);
  EXPECT_EQ(master.rows.front().mode, core::TestMode::uniaxial);
  EXPECT_EQ(master.rows.front().time_s, 0.00281764);
  EXPECT_EQ(master.rows.front().modulus_MPa, 1714.266);
  EXPECT_TRUE(std::isnan(master.rows.front().temperature_C));
  const auto raw = data::read_relaxation_table(dataset("pyvisco-time-raw.csv"));  // T in °C
  ASSERT_EQ(raw.rows.size(), 210u);
  EXPECT_EQ(raw.rows.front().time_s, 10.0);
  EXPECT_EQ(raw.rows.front().temperature_C, -49.9612);
  EXPECT_EQ(raw.rows.back().set, "20");
  EXPECT_TRUE(data::looks_like_relaxation_csv(core::read_file(dataset("pyvisco-time-master.csv"))));
  EXPECT_FALSE(data::looks_like_relaxation_csv(core::read_file(dataset("pyvisco-freq-master.csv"))));
}

TEST(Relaxation, ShearUnitsAndErrors) {
  const auto g = data::parse_relaxation_table("t,G_relax\ns,kPa\n1,500\n", "g.csv");
  EXPECT_EQ(g.rows.front().mode, core::TestMode::shear);
  EXPECT_EQ(g.rows.front().modulus_MPa, 0.5);
  const auto fails_at = [](const std::string& text, int line, int column) {
    try {
      data::parse_relaxation_table(text, "bad.csv");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_EQ(e.column(), column) << e.what();
    }
  };
  fails_at("t,E_relax\nms,MPa\n1,2\n", 2, 1);
  fails_at("t,E_relax\ns,MPa\n1,-2\n", 3, 2);
  fails_at("t,E_relax\ns,MPa\n0,2\n", 3, 1);
  fails_at("t,E_relax,x\ns,MPa,-\n1,2,3\n", 1, 3);
  fails_at("t,E_relax\ns,MPa\n1\n", 3, 2);
}

}  // namespace
