// A master curve's shifts as a text table for reading and as CSV (data, shortest round trip).
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "fitlib/core/format.hpp"
#include "fitlib/fit/master_curve.hpp"

namespace fitlib::fit {

namespace {

// A figure of the table, "-" where there is none (the reference isotherm's pair rms, a law that
// needs more isotherms): every --master-curve table printed "nan".
std::string figure(double value, int significant = 0) {
  if (!std::isfinite(value)) return "-";
  return significant > 0 ? core::format_number(value, significant) : core::format_number(value);
}

std::string column(double value, int width, int decimals) {
  char text[64];
  if (std::isfinite(value)) std::snprintf(text, sizeof text, "%*.*f", width, decimals, value);
  else std::snprintf(text, sizeof text, "%*s", width, "-");
  return text;
}

}  // namespace

std::string format_shift_table(const MasterCurve& curve) {
  std::ostringstream s;
  s << "master curve: " << curve.isotherms.size() << " isotherms, T_ref = " << core::format_number(curve.reference_C, 6)
    << " degC\n";
  s << "      T_C   log10_aT   log10_bT   pair_rms  overlap  set\n";
  for (const auto& iso : curve.isotherms) {
    s << column(iso.temperature_C, 9, 3) << " " << column(iso.log10_aT, 10, 4) << " " << column(iso.log10_bT, 10, 4)
      << " " << column(iso.pair_rms_decades, 10, 4) << " " << std::setw(8) << iso.pair_overlap_points << "  " << iso.set
      << "\n";
  }
  s << "WLF: C1 = " << figure(curve.wlf.C1, 6) << ", C2 = " << figure(curve.wlf.C2_K, 6) << " K, rms "
    << figure(curve.wlf.rms_decades, 3) << " decades\n";
  s << "Arrhenius: E_a = " << figure(curve.arrhenius.activation_energy_kJ_mol, 6) << " kJ/mol, rms "
    << figure(curve.arrhenius.rms_decades, 3) << " decades\n";
  for (const auto& m : curve.messages) s << "note: " << m << "\n";
  return s.str();
}

std::string shift_table_csv(const MasterCurve& curve) {
  std::ostringstream s;
  s << "# fitlib master curve shifts, T_ref = " << core::format_number(curve.reference_C) << " degC\n";
  s << "# WLF C1 = " << figure(curve.wlf.C1) << ", C2_K = " << figure(curve.wlf.C2_K)
    << ", rms_decades = " << figure(curve.wlf.rms_decades, 6) << "\n";
  s << "# Arrhenius E_a_kJ_mol = " << figure(curve.arrhenius.activation_energy_kJ_mol)
    << ", rms_decades = " << figure(curve.arrhenius.rms_decades, 6) << "\n";
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
