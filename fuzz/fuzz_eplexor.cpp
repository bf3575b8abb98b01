// EPLEXOR "Excel Export" workbooks (.xls, docs/data.md §5), read as `fitcli fit --data F.xls` does.
// libfreexl opens files only by path (no memory API in Debian's 1.0.6), so the input goes to a
// file of this process first. libfreexl itself is Debian's uninstrumented build: its crashes are
// still caught (ASan), but coverage guidance comes from fitlib's side of the reader only.
#include "fitlib/data/eplexor.hpp"
#include "table_checks.hpp"

using fitlib::fuzz::require_finite;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fitlib::fuzz::write_input(data, size, ".xls");
  return fitlib::fuzz::run_reader([&] {
    const auto exported = fitlib::data::read_eplexor(path);
    fitlib::fuzz::check_table(exported.table);
    if (!exported.has_shift_list) return;
    require_finite(exported.shifts.reference_C, "EPLEXOR Ref.Temp.");
    for (const auto& s : exported.shifts.factors) {
      require_finite(s.temperature_C, "shift temperature");
      require_finite(s.log10_aT, "log10 a_T");
    }
  });
}
