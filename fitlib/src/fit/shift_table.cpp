// A master curve's shifts as a text table for reading and as CSV (data, shortest round trip).
#include <cstdio>
#include <sstream>

#include "fitlib/core/format.hpp"
#include "fitlib/fit/master_curve.hpp"

namespace fitlib::fit {

std::string format_shift_table(const MasterCurve& curve) {
  std::ostringstream s;
  s << "master curve: " << curve.isotherms.size() << " isotherms, T_ref = " << core::format_number(curve.reference_C, 6)
    << " degC\n";
  s << "      T_C   log10_aT   log10_bT   pair_rms  overlap  set\n";
  for (const auto& iso : curve.isotherms) {
    char line[160];
    std::snprintf(line, sizeof line, "%9.3f %10.4f %10.4f %10.4f %8d  %s\n", iso.temperature_C, iso.log10_aT,
                  iso.log10_bT, iso.pair_rms_decades, iso.pair_overlap_points, iso.set.c_str());
    s << line;
  }
  s << "WLF: C1 = " << core::format_number(curve.wlf.C1, 6) << ", C2 = " << core::format_number(curve.wlf.C2_K, 6)
    << " K, rms " << core::format_number(curve.wlf.rms_decades, 3) << " decades\n";
  s << "Arrhenius: E_a = " << core::format_number(curve.arrhenius.activation_energy_kJ_mol, 6) << " kJ/mol, rms "
    << core::format_number(curve.arrhenius.rms_decades, 3) << " decades\n";
  for (const auto& m : curve.messages) s << "note: " << m << "\n";
  return s.str();
}

std::string shift_table_csv(const MasterCurve& curve) {
  std::ostringstream s;
  s << "# fitlib master curve shifts, T_ref = " << core::format_number(curve.reference_C) << " degC\n";
  s << "# WLF C1 = " << core::format_number(curve.wlf.C1) << ", C2_K = " << core::format_number(curve.wlf.C2_K)
    << ", rms_decades = " << core::format_number(curve.wlf.rms_decades, 6) << "\n";
  s << "# Arrhenius E_a_kJ_mol = " << core::format_number(curve.arrhenius.activation_energy_kJ_mol)
    << ", rms_decades = " << core::format_number(curve.arrhenius.rms_decades, 6) << "\n";
  s << "T_C,log10_aT,log10_bT,set\n";
  for (const auto& iso : curve.isotherms) {
    std::string set = iso.set;
    if (set.find_first_of(",\"") != std::string::npos) {
      std::string q = "\"";
      for (char c : set) q += c == '"' ? std::string("\"\"") : std::string(1, c);
      set = q + "\"";
    }
    s << core::format_number(iso.temperature_C) << "," << core::format_number(iso.log10_aT) << ","
      << core::format_number(iso.log10_bT) << "," << set << "\n";
  }
  return s.str();
}

}  // namespace fitlib::fit
