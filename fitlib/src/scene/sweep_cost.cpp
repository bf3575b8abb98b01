// The work cap of a sweep in core-hours (docs/sweep.md "Work cap"): a case costs what its life's
// fidelity level costs, measured on the 2-core reference machine, so a 10^6-case sweep at the
// beam level (0.19 core-hours) runs and one at the elastic level (about 280 core-hours) is refused
// before the first case.
#include <algorithm>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/scene/planner.hpp"
#include "sweep_case.hpp"

namespace fitlib::scene {
namespace {

bool needs_life(const Sweep& sweep) {
  for (const auto& c : sweep.columns)
    if (c == "fidelity" || c == "governing_mode" || c.find("life") != std::string::npos) return true;
  return false;
}

// Axes whose values can change a case's fidelity: [life] keys, the cards, the [segment] table.
bool sets_fidelity(const SweepAxis& axis) {
  for (const char* prefix : {"life.", "belt.materials.", "segment."})
    if (axis.key.rfind(prefix, 0) == 0) return true;
  return false;
}

double case_cost_s(const Sweep& sweep, const SweepCase& c, bool life) {
  if (!life) return kSweepCaseCostS.beam;  // the load cycle alone: at most the beam level's cost
  const core::Fidelity level = choose_life_plan(case_scene(sweep, c)).fidelity;
  return level == core::Fidelity::complete  ? kSweepCaseCostS.complete
         : level == core::Fidelity::elastic ? kSweepCaseCostS.elastic
                                            : kSweepCaseCostS.beam;
}

}  // namespace

double sweep_cost_core_hours(const Sweep& sweep) {
  const bool life = needs_life(sweep);
  std::vector<std::size_t> varied;  // the axes that set the fidelity, enumerated; the others multiply
  double repeats = 1.0, combos = 1.0;
  for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
    const double n = static_cast<double>(sweep.axes[a].values.size());
    if (life && sets_fidelity(sweep.axes[a])) varied.push_back(a), combos *= n;
    else repeats *= n;
  }
  double seconds = 0.0;
  for (std::size_t s = 0; s < sweep.scenes.size(); ++s) {
    SweepCase c;
    c.scene = s;
    c.value.assign(sweep.axes.size(), 0);
    if (combos > 256) {  // too many to try: each value alone, the dearest for every case
      double worst = case_cost_s(sweep, c, life);
      for (std::size_t a : varied)
        for (std::size_t v = 0; v < sweep.axes[a].values.size(); ++v, c.value[a] = 0) {
          c.value[a] = v;
          worst = std::max(worst, case_cost_s(sweep, c, life));
        }
      seconds += worst * combos * repeats;
      continue;
    }
    for (double k = 0; k < combos; ++k) {  // mixed radix over the varied axes
      std::size_t rest = static_cast<std::size_t>(k);
      for (auto a = varied.rbegin(); a != varied.rend(); ++a) {
        c.value[*a] = rest % sweep.axes[*a].values.size();
        rest /= sweep.axes[*a].values.size();
      }
      seconds += case_cost_s(sweep, c, life) * repeats;
    }
  }
  return seconds / 3600.0;
}

void check_sweep_cost(const Sweep& sweep) {
  const double hours = sweep_cost_core_hours(sweep);
  if (hours > kMaxSweepCoreHours)
    throw core::InputError("the grid of " + std::to_string(sweep.case_count) + " cases would take about " +
                               core::format_number(hours, 3) + " core-hours at its cases' life fidelity (beam " +
                               core::format_number(kSweepCaseCostS.beam * 1e3, 3) + " ms, elastic " +
                               core::format_number(kSweepCaseCostS.elastic, 3) + " s, complete " +
                               core::format_number(kSweepCaseCostS.complete, 3) +
                               " s per case), above the work cap " + core::format_number(kMaxSweepCoreHours) +
                               " core-hours (README, work caps); split the sweep or choose a cheaper life.fidelity",
                           sweep.path, 0, 0, "life.fidelity");
}

}  // namespace fitlib::scene
