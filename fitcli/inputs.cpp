#include "inputs.hpp"

#include <iostream>

#include "fitlib/core/io.hpp"
#include "fitlib/data/eplexor.hpp"

namespace fitcli {

fitlib::data::DynamicTestTable read_tables(const std::vector<std::string>& paths, const std::string& format,
                                           const fitlib::data::ReadOptions& read) {
  using namespace fitlib;
  data::DynamicTestTable all;
  for (const auto& path : paths) {
    data::DynamicTestTable one;
    if (format == "eplexor" || data::is_ole_compound_file(core::read_file(path))) {
      auto x = data::read_eplexor(path, read);
      if (x.has_shift_list)
        std::cerr << "fitcli: note: " << path << ": EPLEXOR master export, Ref.Temp. " << x.shifts.reference_C
                  << " degC, WLF C1 " << x.wlf_C1 << ", C2 " << x.wlf_C2_K << " K (" << x.shifts.factors.size()
                  << " shifts)\n";
      one = std::move(x.table);
    } else {
      one = data::read_dynamic_table(path, read);
    }
    all.rows.insert(all.rows.end(), one.rows.begin(), one.rows.end());
    all.source_files.insert(all.source_files.end(), one.source_files.begin(), one.source_files.end());
    all.source_sha256.insert(all.source_sha256.end(), one.source_sha256.begin(), one.source_sha256.end());
    all.warnings.insert(all.warnings.end(), one.warnings.begin(), one.warnings.end());
  }
  return all;
}

bool is_relaxation_data(const std::vector<std::string>& paths, const std::string& format) {
  return format == "pyvisco" && !paths.empty() &&
         fitlib::data::looks_like_relaxation_csv(fitlib::core::read_file(paths.front()));
}

fitlib::data::RelaxationTable read_relaxation_tables(const std::vector<std::string>& paths) {
  fitlib::data::RelaxationTable table;
  for (const auto& path : paths) {
    auto one = fitlib::data::read_relaxation_table(path);
    table.rows.insert(table.rows.end(), one.rows.begin(), one.rows.end());
    table.source_files.insert(table.source_files.end(), one.source_files.begin(), one.source_files.end());
    table.source_sha256.insert(table.source_sha256.end(), one.source_sha256.begin(), one.source_sha256.end());
  }
  return table;
}

}  // namespace fitcli
