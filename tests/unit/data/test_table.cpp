// Dynamic-test table reader/writer (formats.md §1): malformed fixtures with exact locations,
// accepted variants, pyvisco import, round trip.
#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include <cmath>
#include <cstring>
#include <set>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/core/units.hpp"

using fitlib::core::InputError;
using fitlib::data::DynamicTestTable;
using fitlib::data::parse_dynamic_table;
using fitlib::data::read_dynamic_table;
using fitlib::data::ReadOptions;
using fitlib::data::TableFormat;
using fitlib::core::TestMode;

namespace {

const std::string kMalformed = std::string(FITLIB_TEST_DATA_DIR) + "/malformed/";
// pyvisco's example files, copied into the repository (datasets/materials, datasets/README.md).
const std::string kPyviscoMaster = std::string(FITLIB_SOURCE_DIR) + "/datasets/materials/pyvisco-freq-master.csv";
const std::string kPyviscoRaw = std::string(FITLIB_SOURCE_DIR) + "/datasets/materials/pyvisco-freq-raw.csv";
const std::string kPyviscoTimeMaster = std::string(FITLIB_SOURCE_DIR) + "/datasets/materials/pyvisco-time-master.csv";
using fitlib::core::kPi;

struct MalformedCase {
  const char* file;
  int line;
  int column;  // 0 = the error concerns the whole line (e.g. a missing column)
  const char* message_part;
  TableFormat format = TableFormat::native;
};

std::ostream& operator<<(std::ostream& os, const MalformedCase& c) { return os << c.file; }

class MalformedTable : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(MalformedTable, ReportsFileLineAndColumn) {
  const MalformedCase& c = GetParam();
  const std::string path = kMalformed + c.file;
  ReadOptions options;
  options.format = c.format;
  try {
    read_dynamic_table(path, options);
    FAIL() << "no error for " << c.file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), c.line) << e.what();
    EXPECT_EQ(e.column(), c.column) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.message_part), std::string::npos) << e.what();
    std::string where = path + ":" + std::to_string(c.line);
    if (c.column > 0) where += ":" + std::to_string(c.column);
    EXPECT_EQ(std::string(e.what()).rfind(where + ": ", 0), 0u) << e.what();
    EXPECT_EQ(fitlib::core::exit_code_for(e), 3);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Fixtures, MalformedTable,
    ::testing::Values(
        MalformedCase{"missing_column.csv", 2, 0, "missing required column 'loss_<U>'"},
        MalformedCase{"unknown_unit.csv", 1, 3, "unknown unit 'psi' in column 'storage_psi'"},
        MalformedCase{"nan_value.csv", 3, 3, "NaN/Inf"},
        MalformedCase{"inf_value.csv", 2, 2, "NaN/Inf"},
        MalformedCase{"negative_frequency.csv", 4, 2, "non-positive frequency"},
        MalformedCase{"zero_storage.csv", 2, 3, "non-positive storage modulus"},
        MalformedCase{"negative_loss.csv", 3, 4, "negative loss modulus"},
        MalformedCase{"negative_weight.csv", 2, 5, "negative weight"},
        MalformedCase{"empty.csv", 1, 0, "no header row"},
        MalformedCase{"bom_only.csv", 1, 0, "no header row"},
        // The BOM is stripped: the first column is `mode`, the typo is in column 5.
        MalformedCase{"bom_bad_header.csv", 1, 5, "unknown column 'temprature_C'"},
        // CRLF: "\r" is not part of the fields, the error is where it is.
        MalformedCase{"crlf_error.csv", 5, 4, "loss modulus 'abc' is not a number"},
        MalformedCase{"duplicate_header.csv", 1, 5, "duplicate column 'storage_kPa'"},
        MalformedCase{"non_number.csv", 2, 3, "'2.5 MPa' is not a number"},
        MalformedCase{"header_only.csv", 1, 0, "no data rows"},
        MalformedCase{"wrong_field_count.csv", 3, 4, "row has 3 fields, header has 4"},
        MalformedCase{"unknown_mode.csv", 2, 1, "unknown test mode 'torsion'"},
        MalformedCase{"pyvisco_bad_unit.csv", 2, 2, "unknown unit 'psi'", TableFormat::pyvisco},
        // A European spreadsheet's export: the whole header is one name; the message says why.
        MalformedCase{"semicolon_separated.csv", 1, 1, "the name holds ';': fitlib reads comma-separated tables"},
        MalformedCase{"tab_separated.csv", 1, 1, "the name holds a tab: fitlib reads comma-separated tables"}));

TEST(Table, SkipBadRowsWarnsForEachSkippedRow) {
  const std::string path = kMalformed + "mixed_bad_rows.csv";
  EXPECT_THROW(read_dynamic_table(path), InputError);
  ReadOptions options;
  options.skip_bad_rows = true;
  const DynamicTestTable table = read_dynamic_table(path, options);
  ASSERT_EQ(table.rows.size(), 3u);
  EXPECT_EQ(table.rows[0].source_line, 2);
  EXPECT_EQ(table.rows[1].source_line, 4);
  EXPECT_EQ(table.rows[2].source_line, 6);
  ASSERT_EQ(table.warnings.size(), 2u);
  EXPECT_NE(table.warnings[0].find(path + ":3:2: non-positive frequency"), std::string::npos)
      << table.warnings[0];
  EXPECT_NE(table.warnings[1].find(path + ":5:3: storage modulus is nan"), std::string::npos)
      << table.warnings[1];
}

TEST(Table, SkipBadRowsKeepsHeaderErrorsAndRefusesAnEmptyResult) {
  ReadOptions options;
  options.skip_bad_rows = true;
  EXPECT_THROW(read_dynamic_table(kMalformed + "unknown_unit.csv", options), InputError);
  try {
    parse_dynamic_table("mode,frequency_Hz,storage_MPa,loss_MPa\nshear,-1,1,0\n", "mem.csv",
                        options);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 1);
    EXPECT_NE(std::string(e.what()).find("no valid data rows (1 skipped)"), std::string::npos);
  }
}

TEST(Table, AcceptsBomCrlfSpacesCommentsAndTrailingEmptyLine) {
  const std::string path = kMalformed + "accepted_bom_crlf_spaces.csv";
  const DynamicTestTable table = read_dynamic_table(path);
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_TRUE(table.warnings.empty());
  const auto& a = table.rows[0];
  EXPECT_EQ(a.condition.mode, TestMode::shear);
  EXPECT_NEAR(a.condition.frequency_Hz, 1.0, 1e-15);  // 6.283185307179586 rad/s
  EXPECT_DOUBLE_EQ(a.storage_MPa, 2.5);                // 2500 kPa
  EXPECT_DOUBLE_EQ(a.loss_MPa, 0.3);
  EXPECT_NEAR(a.condition.temperature_C, 23.0, 1e-12);  // 296.15 K
  EXPECT_EQ(a.material, "rubber, black");
  EXPECT_EQ(a.set, "A");
  EXPECT_EQ(a.source_line, 4);
  EXPECT_EQ(a.source_file, path);
  const auto& b = table.rows[1];
  EXPECT_EQ(b.condition.mode, TestMode::uniaxial);
  EXPECT_NEAR(b.condition.frequency_Hz, 10.0, 1e-14);
  EXPECT_DOUBLE_EQ(b.storage_MPa, 7.0);
  EXPECT_DOUBLE_EQ(b.loss_MPa, 1.4);
  EXPECT_NEAR(b.condition.temperature_C, 80.0, 1e-12);
  EXPECT_EQ(b.set, "B");
  EXPECT_EQ(b.source_line, 6);
  // Independent fingerprint: `sha256sum accepted_bom_crlf_spaces.csv`.
  ASSERT_EQ(table.source_sha256.size(), 1u);
  EXPECT_EQ(table.source_sha256[0],
            "6a66823a173cd09232c87b0a8943dced26f8b1f49298df41af606041cadf7a78");
}

TEST(Table, AbsoluteModulusWithLossAngleOrTanDelta) {
  const DynamicTestTable table = read_dynamic_table(kMalformed + "accepted_polar.csv");
  ASSERT_EQ(table.rows.size(), 2u);
  const auto& a = table.rows[0];
  EXPECT_NEAR(a.storage_MPa, 10.0 * std::sqrt(3.0) / 2.0, 1e-13);  // 0.01 GPa at 30°
  EXPECT_NEAR(a.loss_MPa, 5.0, 1e-13);
  EXPECT_EQ(a.condition.strain_amplitude, 0.01);
  EXPECT_EQ(a.condition.mean_strain, 0.01);
  EXPECT_TRUE(a.has_mean_modulus);
  EXPECT_EQ(a.mean_modulus_MPa, 8.5);
  EXPECT_EQ(a.condition.orientation, "22");
  EXPECT_EQ(a.weight, 2.0);
  const auto& b = table.rows[1];  // empty optional cells take their defaults
  EXPECT_NEAR(b.storage_MPa, 2.0 / std::sqrt(2.0), 1e-13);
  EXPECT_NEAR(b.loss_MPa, 2.0 / std::sqrt(2.0), 1e-13);
  EXPECT_EQ(b.condition.mean_strain, 0.0);
  EXPECT_FALSE(b.has_mean_modulus);
  EXPECT_EQ(b.weight, 1.0);
  EXPECT_TRUE(std::isnan(b.condition.temperature_C));

  const auto tan = parse_dynamic_table(
      "mode,frequency_Hz,abs_modulus_MPa,tan_delta\ncompression,1,5,0.75\n", "mem.csv");
  EXPECT_EQ(tan.rows[0].condition.mode, TestMode::uniaxial);
  EXPECT_NEAR(tan.rows[0].storage_MPa, 4.0, 1e-14);  // 3-4-5 triangle
  EXPECT_NEAR(tan.rows[0].loss_MPa, 3.0, 1e-14);
}

TEST(Table, HeaderRules) {
  const auto error_at = [](const std::string& text, const ReadOptions& options = {}) {
    try {
      parse_dynamic_table(text, "mem.csv", options);
    } catch (const InputError& e) {
      return std::make_pair(e.line(), e.column());
    }
    return std::make_pair(-1, -1);
  };
  // Alternatives for one quantity are duplicates.
  EXPECT_EQ(error_at("mode,frequency_Hz,storage_MPa,loss_MPa,angular_frequency_rad_s\n"),
            std::make_pair(1, 5));
  // storage/loss and abs_modulus/tan_delta together are refused (at the polar column).
  EXPECT_EQ(error_at("mode,frequency_Hz,storage_MPa,loss_MPa,tan_delta\nshear,1,1,0.1,0.1\n"),
            std::make_pair(1, 5));
  EXPECT_EQ(error_at("mode,frequency_Hz,abs_modulus_MPa\nshear,1,1\n"), std::make_pair(1, 0));
  EXPECT_EQ(error_at("mode,frequency_Hz,storage_MPa,loss_MPa,\nshear,1,1,0.1,\n"),
            std::make_pair(1, 5));  // empty column name
  // No mode column: an error unless a default mode is given.
  const std::string no_mode = "frequency_Hz,storage_MPa,loss_MPa\n1,2,0.2\n";
  EXPECT_EQ(error_at(no_mode), std::make_pair(1, 0));
  ReadOptions options;
  options.has_default_mode = true;
  options.default_mode = TestMode::bulk;
  EXPECT_EQ(parse_dynamic_table(no_mode, "mem.csv", options).rows[0].condition.mode,
            TestMode::bulk);
  // Unknown columns: an error by default, a warning on request; x_ columns are notes.
  const std::string extra = "mode,frequency_Hz,storage_MPa,loss_MPa,cycles,x_note\nshear,1,2,0.2,5,a\n";
  EXPECT_EQ(error_at(extra), std::make_pair(1, 5));
  ReadOptions lenient;
  lenient.allow_unknown_columns = true;
  const auto table = parse_dynamic_table(extra, "mem.csv", lenient);
  ASSERT_EQ(table.warnings.size(), 1u);
  EXPECT_NE(table.warnings[0].find("mem.csv:1:5: unknown column 'cycles'"), std::string::npos);
  EXPECT_EQ(table.warnings[0].find("relaxation data"), std::string::npos);  // no time column: no such hint
  // A time column: relaxation data, which the pyvisco layout reads; the message says how.
  try {
    parse_dynamic_table("time_s,modulus_MPa\n0.001,12.1\n", "relax.csv");
    ADD_FAILURE() << "a relaxation table read as a dynamic test";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("relaxation data (a modulus over time) are read in pyvisco's layout: a "
                                         "header t,E_relax"), std::string::npos) << e.what();
  }
  // Row checks beyond the fixtures.
  EXPECT_EQ(error_at("mode,frequency_Hz,storage_MPa,loss_MPa,temperature_K\nshear,1,2,0.2,-3\n"),
            std::make_pair(2, 5));
  EXPECT_EQ(error_at("mode,frequency_Hz,storage_MPa,loss_MPa,orientation\nshear,1,2,0.2,14\n"),
            std::make_pair(2, 5));
  EXPECT_EQ(error_at("mode,frequency_Hz,storage_MPa,loss_MPa\nshear,1,2,\"0.2\n"),
            std::make_pair(2, 4));  // unterminated quote
  EXPECT_EQ(error_at("mode,frequency_Hz,storage_MPa,loss_MPa\nshear,,2,0.2\n"),
            std::make_pair(2, 2));  // empty required cell
}

TEST(Table, RoundTripIsBitExact) {
  DynamicTestTable table;
  const double awkward[] = {0.1, 1.0 / 3.0, 1e-300, 6.02214076e23, 2.0 / 7.0, 5e-324};
  for (int i = 0; i < 6; ++i) {
    fitlib::data::DynamicTestRow row;
    row.condition.mode = static_cast<TestMode>(i % 3);
    row.condition.orientation = i % 2 ? "3232" : "";
    row.condition.frequency_Hz = awkward[i] + 1.0 / 7.0;
    row.condition.temperature_C = i == 2 ? std::nan("") : awkward[i] * 100.0 - 40.0;
    row.condition.strain_amplitude = awkward[(i + 1) % 6];
    row.condition.mean_strain = -awkward[(i + 2) % 6];
    row.storage_MPa = 1.0 + awkward[i];
    row.loss_MPa = awkward[(i + 3) % 6];
    row.has_mean_modulus = i % 2 == 0;
    row.mean_modulus_MPa = row.has_mean_modulus ? -awkward[i] : 0.0;
    row.weight = awkward[(i + 4) % 6];
    row.material = i == 1 ? "rubber, \"black\"" : "m" + std::to_string(i);
    row.specimen = i == 3 ? " padded " : "";
    row.set = i == 4 ? "#5" : std::to_string(i);
    table.rows.push_back(row);
  }
  const std::string path = fitlib_test::temp_path("fitlib_roundtrip.csv");
  fitlib::data::write_dynamic_table(path, table);
  const DynamicTestTable back = read_dynamic_table(path);
  ASSERT_EQ(back.rows.size(), table.rows.size());
  const auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const auto& a = table.rows[i];
    const auto& b = back.rows[i];
    EXPECT_EQ(a.condition.mode, b.condition.mode);
    EXPECT_EQ(a.condition.orientation, b.condition.orientation);
    EXPECT_TRUE(same_bits(a.condition.frequency_Hz, b.condition.frequency_Hz)) << i;
    EXPECT_EQ(a.condition.has_temperature(), b.condition.has_temperature());
    if (a.condition.has_temperature()) {
      EXPECT_TRUE(same_bits(a.condition.temperature_C, b.condition.temperature_C)) << i;
    }
    EXPECT_TRUE(same_bits(a.condition.strain_amplitude, b.condition.strain_amplitude)) << i;
    EXPECT_TRUE(same_bits(a.condition.mean_strain, b.condition.mean_strain)) << i;
    EXPECT_TRUE(same_bits(a.storage_MPa, b.storage_MPa)) << i;
    EXPECT_TRUE(same_bits(a.loss_MPa, b.loss_MPa)) << i;
    EXPECT_EQ(a.has_mean_modulus, b.has_mean_modulus);
    if (a.has_mean_modulus) {
      EXPECT_TRUE(same_bits(a.mean_modulus_MPa, b.mean_modulus_MPa)) << i;
    }
    EXPECT_TRUE(same_bits(a.weight, b.weight)) << i;
    EXPECT_EQ(a.material, b.material);
    EXPECT_EQ(a.specimen, b.specimen);
    EXPECT_EQ(a.set, b.set);
  }
  std::remove(path.c_str());
}

TEST(Table, PyviscoMasterCurve) {
  ReadOptions options;
  options.format = TableFormat::pyvisco;
  const auto table = read_dynamic_table(kPyviscoMaster, options);
  ASSERT_EQ(table.rows.size(), 206u);
  const auto& first = table.rows.front();
  EXPECT_EQ(first.condition.mode, TestMode::uniaxial);
  EXPECT_EQ(first.condition.frequency_Hz, 1e-12);
  EXPECT_EQ(first.storage_MPa, 88.79651575665739);
  EXPECT_EQ(first.loss_MPa, 10.502460140936773);
  EXPECT_FALSE(first.condition.has_temperature());
  EXPECT_EQ(first.source_line, 3);
  EXPECT_EQ(table.rows.back().condition.frequency_Hz, 1e14);
  for (std::size_t i = 1; i < table.rows.size(); ++i)
    EXPECT_GT(table.rows[i].condition.frequency_Hz, table.rows[i - 1].condition.frequency_Hz);
  // The native reader refuses pyvisco's header (column 'f' is unknown there).
  EXPECT_THROW(read_dynamic_table(kPyviscoMaster), InputError);
}

TEST(Table, PyviscoRawIsothermsWithBom) {
  ReadOptions options;
  options.format = TableFormat::pyvisco;
  const auto table = read_dynamic_table(kPyviscoRaw, options);
  ASSERT_EQ(table.rows.size(), 210u);
  std::set<std::string> sets;
  for (const auto& row : table.rows) sets.insert(row.set);
  EXPECT_EQ(sets.size(), 21u);
  const auto& first = table.rows.front();
  EXPECT_EQ(first.condition.frequency_Hz, 0.1);
  EXPECT_EQ(first.storage_MPa, 8097.175545);
  EXPECT_EQ(first.loss_MPa, 93.07449045);
  EXPECT_EQ(first.condition.temperature_C, -49.9612);
  EXPECT_EQ(first.set, "0");
  const auto& last = table.rows.back();
  EXPECT_EQ(last.condition.frequency_Hz, 100.0);
  EXPECT_EQ(last.storage_MPa, 585.8391184);
  EXPECT_EQ(last.loss_MPa, 223.41197);
  EXPECT_EQ(last.condition.temperature_C, 100.001);
  EXPECT_EQ(last.set, "20");
  EXPECT_EQ(last.source_line, 212);
}

TEST(Table, PyviscoShearUnitsAndTimeDomainRefusal) {
  ReadOptions options;
  options.format = TableFormat::pyvisco;
  const auto g = parse_dynamic_table("f, G_stor, G_loss, T\nHz, kPa, kPa, K\n2, 2500, 300, 300\n",
                                     "mem.csv", options);
  EXPECT_EQ(g.rows[0].condition.mode, TestMode::shear);
  EXPECT_DOUBLE_EQ(g.rows[0].storage_MPa, 2.5);
  EXPECT_DOUBLE_EQ(g.rows[0].loss_MPa, 0.3);
  EXPECT_NEAR(g.rows[0].condition.temperature_C, 26.85, 1e-12);
  try {
    read_dynamic_table(kPyviscoTimeMaster, options);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 1);
    EXPECT_EQ(e.column(), 1);
  }
  EXPECT_THROW(parse_dynamic_table("f, E_stor, G_loss\nHz, MPa, MPa\n1,2,3\n", "m", options),
               InputError);
}

TEST(Table, SeveralFilesKeepOrderAndFingerprints) {
  ReadOptions options;
  options.format = TableFormat::pyvisco;
  const auto both = fitlib::data::read_dynamic_tables(
      {kPyviscoMaster, kPyviscoRaw}, options);
  EXPECT_EQ(both.rows.size(), 416u);
  ASSERT_EQ(both.source_sha256.size(), 2u);
  EXPECT_EQ(both.source_files[1], kPyviscoRaw);
  EXPECT_EQ(both.rows[206].source_file, kPyviscoRaw);
  EXPECT_NE(both.source_sha256[0], both.source_sha256[1]);
}

}  // namespace
