// A fatigue card from observed lives: fit_life_law per mode on top of a start card (life_fit.hpp).
#include <algorithm>
#include <cmath>
#include <utility>

#include "fitlib/core/error.hpp"
#include "fitlib/fatigue/life_fit.hpp"

namespace fitlib::fatigue {

nlohmann::json life_fit_json(const LifeFitResult& fit) {
  nlohmann::json constants = nlohmann::json::object();
  for (const ConstantEstimate& c : fit.constants) {
    nlohmann::json e = {{"value", c.value}, {"unit", c.unit}, {"fixed", c.fixed}};
    if (c.has_interval) e["std_error"] = c.std_error, e["ci95"] = {c.ci95_low, c.ci95_high};
    constants[c.name] = e;
  }
  nlohmann::json j = {{"cases", fit.cases}, {"runouts", fit.runouts}, {"rms_log10_error", fit.rms_log10_error},
                      {"note", fit.note}, {"constants", constants}};
  if (!fit.violated_runouts.empty()) j["violated_runouts"] = fit.violated_runouts;
  if (!fit.rejected.empty()) j["rejected"] = fit.rejected;
  return j;
}

namespace {

// The largest peak of each case of the mode (over its points) spans less than this factor: n,
// the slope of log N over log σ, then rests on a life spread over a narrow stress range. Said
// where n has no interval to show it (too few cases); with one, σ0's spread warning says it.
constexpr double kNarrowStressSpan = 1.25;

// "runout A (…) fails" / "runouts A (…), B (…) fail".
std::string runouts_fail(const std::vector<std::string>& runouts) {
  std::string out = runouts.size() == 1 ? "runout " : "runouts ";
  for (std::size_t k = 0; k < runouts.size(); ++k) out += (k ? ", " : "") + runouts[k];
  return out + (runouts.size() == 1 ? " fails" : " fail");
}

void warn_about(const LifeFitResult& f, const std::vector<ObservedLife>& cases, std::vector<std::string>& warnings) {
  const std::string mode = to_string(f.mode);
  double lowest = INFINITY, highest = 0.0;
  for (const ObservedLife& c : cases) {
    if (c.mode != f.mode || c.runout) continue;
    double largest = 0.0;
    for (const auto& peaks : c.point_peaks_MPa)
      for (double p : peaks) largest = std::max(largest, p);
    lowest = std::min(lowest, largest), highest = std::max(highest, largest);
  }
  const ConstantEstimate& n = f.constants[1];
  if (!n.fixed && !n.has_interval && f.cases > 1 && highest < kNarrowStressSpan * lowest)
    warnings.push_back(mode + ": the cases' largest stress peaks span only a factor " +
                       core::short_number(highest / lowest) + " (" + core::short_number(lowest) + " to " +
                       core::short_number(highest) + " MPa), so n = " + core::short_number(n.value) +
                       " rests on the lives' spread over that narrow range; tests over a wider load range "
                       "tell n, or hold it (--fix-n)");
  // As many free constants as cases: an exact fit, whatever the law's worth (held ones: the start's).
  std::string free, held;
  int free_count = 0;
  for (const ConstantEstimate& c : f.constants) {
    std::string& list = c.fixed ? held : free;
    list += (list.empty() ? "" : ", ") + c.name;
    free_count += c.fixed ? 0 : 1;
  }
  if (free_count >= f.cases)
    warnings.push_back(mode + ": " + std::to_string(f.cases) + " case(s) for the free constant(s) " + free +
                       ": the fit passes through every case, so nothing shows how well (6.31) describes them" +
                       (held.empty() ? "" : "; " + held + " held at the start card's value(s)"));
  if (f.rms_log10_error > kScatterWarning_log10)
    warnings.push_back(mode + ": the observed lives scatter around the fit by a factor " +
                       core::short_number(std::pow(10.0, f.rms_log10_error)) + " (rms log10 error " +
                       core::short_number(f.rms_log10_error) + "): (6.31) with one design point does not describe "
                       "these cases");
  if (n.has_interval && n.ci95_low <= 0.0)
    warnings.push_back(mode + ": n's 95 % interval [" + core::short_number(n.ci95_low) + ", " +
                       core::short_number(n.ci95_high) + "] reaches zero: these cases do not show how fast the "
                       "life falls with the stress (more cases over a wider load range, or hold n with --fix-n)");
  const ConstantEstimate& b = f.constants.back();
  if (b.has_interval && b.ci95_low <= 0.0)
    warnings.push_back(mode + ": b's 95 % interval [" + core::short_number(b.ci95_low) + ", " +
                       core::short_number(b.ci95_high) + "] 1/degC reaches zero: these cases do not show that heat "
                       "shortens the life (hold b with --fix-b)");
  if (!f.violated_runouts.empty())
    warnings.push_back(mode + ": the fitted law says " + runouts_fail(f.violated_runouts) +
                       " before the test stopped (by more than a factor " +
                       core::short_number(std::pow(10.0, kScatterWarning_log10)) +
                       "): the failures and the runouts disagree about this mode's law");
  const ConstantEstimate& s0 = f.constants.front();
  if (s0.has_interval && s0.ci95_high > kSpreadWarning * s0.ci95_low)
    warnings.push_back(mode + ": sigma0's 95 % interval [" + core::short_number(s0.ci95_low) + ", " +
                       core::short_number(s0.ci95_high) + "] MPa spans more than a factor " +
                       core::short_number(kSpreadWarning) +
                       ": the cases' stresses span too narrow a range to tell sigma0 from n");
}

}  // namespace

LifeCardFit fit_life_card(const std::vector<ObservedLife>& cases, const FatigueCard& start, const HeldConstants& held) {
  LifeCardFit out;
  out.card = start;
  out.card.levels.clear();  // the start card's per-level constants were calibrated to its laws, not to the fitted ones
  nlohmann::json record = nlohmann::json::object();
  bool fitted = false;  // a mode's fit went into the card
  for (Mode mode : {Mode::radial_crack, Mode::separation}) {
    bool any = false;
    for (const ObservedLife& c : cases) any = any || (c.mode == mode && !c.runout);
    if (!any) {
      out.warnings.push_back(std::string(to_string(mode)) +
                             ": no case failed in this mode; the start card's constants are kept");
      // Runouts alone bound the life from below but fix no law; they can still refute the start's.
      const auto violated = violated_runouts(cases, mode, start.law(mode), start.reference_temperature_C, 0.0);
      if (!violated.empty())
        out.warnings.push_back(std::string(to_string(mode)) + ": the start card's constants say " +
                               runouts_fail(violated) + " before the test stopped");
      continue;
    }
    LifeFitOptions o;
    o.reference_temperature_C = start.reference_temperature_C;
    o.start = start.law(mode);
    o.fix_n = held.n, o.fix_b = held.b;
    LifeFitResult fit = fit_life_law(cases, mode, o);
    if (fit.law.n <= kExponentMin * (1 + 1e-9) || fit.law.n >= kExponentMax * (1 - 1e-9)) {
      fit.rejected = "n went to its bound " + core::short_number(fit.law.n) + " (sigma0 " +
                     core::short_number(fit.law.sigma0_MPa) + " MPa): across these cases the lives do not fall with "
                     "the stress as (6.31) needs";
      out.warnings.push_back(std::string(to_string(mode)) + ": not fitted: " + fit.rejected +
                             "; the start card's constants are kept");
    } else {
      out.card.law(mode) = fit.law;
      warn_about(fit, cases, out.warnings);
      fitted = true;
    }
    record[to_string(mode)] = life_fit_json(fit);
    out.fits.push_back(std::move(fit));
  }
  if (out.fits.empty())  // every case a runout (a case always has a mode, so only runouts leave none)
    throw core::InputError("no life test failed (" + std::to_string(cases.size()) +
                               " runout case(s)): runouts bound the lives from below but fix no constant; the fit "
                               "needs tests that failed",
                           "", 0, 0, "failure_mode");
  if (!fitted) {
    std::string why;
    for (const LifeFitResult& f : out.fits) why += std::string(why.empty() ? "" : "; ") + to_string(f.mode) + ": " + f.rejected;
    throw core::NumericalError("fatigue: no failure mode could be fitted (" + why + ")");
  }
  const std::optional<core::Fidelity>& crack = out.card.radial_crack.stress_fidelity;
  const std::optional<core::Fidelity>& separation = out.card.separation.stress_fidelity;
  if (crack && separation && *crack != *separation)
    out.warnings.push_back(std::string("the card's radial_crack constants are of ") + core::to_string(*crack) +
                           "-level stresses, its separation constants of " + core::to_string(*separation) +
                           "-level ones: a life at either level reads one mode off "
                           "its constants' scale (fitcli life warns which)");
  out.card.provenance = {{"start_card", start.name}, {"life_fit", record}};
  return out;
}

}  // namespace fitlib::fatigue
