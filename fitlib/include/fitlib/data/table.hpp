#pragma once
// Dynamic-test tables (docs/formats.md §1): one row per measured point, moduli in MPa.
#include <string>
#include <vector>

#include "fitlib/core/test_condition.hpp"

namespace fitlib::data {

struct DynamicTestRow {
  core::TestCondition condition;  // mode, orientation, frequency, temperature, amplitude, mean
  double storage_MPa = 0.0;        // E′ or G′ (K′ for bulk)
  double loss_MPa = 0.0;           // E″ or G″
  double mean_modulus_MPa = 0.0;   // valid only when has_mean_modulus
  bool has_mean_modulus = false;
  double weight = 1.0;
  std::string material, specimen, set;
  std::string source_file;  // where the row came from, for messages
  int source_line = 0;      // 1-based line in source_file
};

struct DynamicTestTable {
  std::vector<DynamicTestRow> rows;
  std::vector<std::string> source_files;
  std::vector<std::string> source_sha256;  // one per source file, of the bytes read
  std::vector<std::string> warnings;       // e.g. rows skipped with --skip-bad-rows
};

enum class TableFormat { native, pyvisco };

struct ReadOptions {
  TableFormat format = TableFormat::native;
  // Mode for files without a `mode` column (pyvisco: uniaxial unless the columns say G).
  bool has_default_mode = false;
  core::TestMode default_mode = core::TestMode::shear;
  // Turn row errors into warnings listing each skipped row (never silently).
  bool skip_bad_rows = false;
  // Native format: a column the contract does not know is an error (a typo such as
  // `temprature_C` would otherwise drop data silently); true turns it into a warning.
  // Columns named `x_...` are user notes and are always ignored without a warning.
  bool allow_unknown_columns = false;
};

// Reads one CSV file. Throws core::InputError naming file, line and column on bad input.
DynamicTestTable read_dynamic_table(const std::string& path, const ReadOptions& options = {});

// Parses the content of a file already in memory (`file_name` is used in messages).
DynamicTestTable parse_dynamic_table(const std::string& bytes, const std::string& file_name,
                                     const ReadOptions& options = {});

// Reads several files into one table (rows in file order).
DynamicTestTable read_dynamic_tables(const std::vector<std::string>& paths,
                                     const ReadOptions& options = {});

// The native CSV text of a table: a comment line, the header, one row per line; doubles in
// shortest round-trip form so that reading the text back gives bit-identical values.
std::string format_dynamic_table(const DynamicTestTable& table);

// Writes a table as native CSV (docs/formats.md §1), atomically.
void write_dynamic_table(const std::string& path, const DynamicTestTable& table);

}  // namespace fitlib::data
