// fitlib's side of the EPLEXOR reader, in this process: the bytes the libfreexl child sends
// (data/eplexor_cells.hpp: xls::parse_sheets) and their interpretation as an export
// (xls::eplexor_from_sheets). Seeds: the bundled workbooks' sheets as the child sends them
// (fuzz/seeds/eplexor_sheets/: xls::serialize_sheets of xls::read_sheets on each bundled .xls,
// its data sheet cut to the first 14 rows).
#include "../fitlib/src/data/eplexor_cells.hpp"
#include "table_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  return fitlib::fuzz::run_reader([&] {
    namespace xls = fitlib::data::xls;
    fitlib::fuzz::check_eplexor(xls::eplexor_from_sheets(xls::parse_sheets(bytes, "sheets.bin"), "sheets.bin"));
  });
}
