#pragma once
// Reading the --data files of fit and plot: native or pyvisco CSV, EPLEXOR .xls (recognised by its
// OLE signature whatever --format says), pyvisco relaxation tables (t, E_relax).
#include <string>
#include <vector>

#include "fitlib/data/relaxation.hpp"
#include "fitlib/data/table.hpp"

namespace fitcli {

// Frequency-domain rows of every file, in order; notes (EPLEXOR shift lists) go to stderr.
fitlib::data::DynamicTestTable read_tables(const std::vector<std::string>& paths, const std::string& format,
                                           const fitlib::data::ReadOptions& read);

// True when --format pyvisco and the first file is a time-domain table.
bool is_relaxation_data(const std::vector<std::string>& paths, const std::string& format);

fitlib::data::RelaxationTable read_relaxation_tables(const std::vector<std::string>& paths);

}  // namespace fitcli
