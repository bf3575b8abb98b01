// EPLEXOR "Excel Export" workbooks (.xls, docs/data.md §5), read as `fitcli fit --data F.xls` does.
// libfreexl opens files only by path (no memory API in Debian's 1.0.6), so the input goes to a
// file of this process first, and libfreexl runs in a child process (~11 executions/s): fitlib's
// side alone is fuzzed fast by fuzz_eplexor_sheets.
#include "fitlib/data/eplexor.hpp"
#include "table_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fitlib::fuzz::write_input(data, size, ".xls");
  return fitlib::fuzz::run_reader([&] { fitlib::fuzz::check_eplexor(fitlib::data::read_eplexor(path)); });
}
