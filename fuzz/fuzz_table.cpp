// Native dynamic-test tables (formats.md §1), parsed from memory as `fitcli fit --data` reads them.
#include "fitlib/data/table.hpp"
#include "table_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fitlib::fuzz::run_reader([&] {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    fitlib::fuzz::check_table(fitlib::data::parse_dynamic_table(bytes, "fuzz.csv"));
  });
}
