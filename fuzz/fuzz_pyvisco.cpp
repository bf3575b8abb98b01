// pyvisco tables (formats.md §1.3), as `fitcli fit --format pyvisco` reads them.
#include "fitlib/data/table.hpp"
#include "table_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fitlib::fuzz::run_reader([&] {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    fitlib::data::ReadOptions options;
    options.format = fitlib::data::TableFormat::pyvisco;
    fitlib::fuzz::check_table(fitlib::data::parse_dynamic_table(bytes, "fuzz.csv", options));
  });
}
