// The card's temperature law on the measured isotherms (docs/fitting.md "Quality verdict"): the
// fit ran on the shifted master table, the card answers at other temperatures through its law.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "fitlib/core/units.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/problem.hpp"
#include "quality.hpp"

namespace fitlib::fit {
namespace {

const char* const kModulusNames[] = {"storage", "loss", "relaxation"};

struct Errors {
  int count = 0;
  double sum = 0.0, max = 0.0, max_at_Hz = 0.0;
};

// (isotherm temperature, modulus) → errors; isotherms within detail::kSameTemperature_C are one.
class IsothermErrors {
 public:
  void add(double temperature_C, int modulus, double model, double data, double at_Hz) {
    if (!(data > 0.0) || !std::isfinite(temperature_C)) return;
    const double err = std::abs(model / data - 1.0);
    Errors& e = errors_[{isotherm(temperature_C), modulus}];
    ++e.count;
    e.sum += err;
    if (err > e.max || e.count == 1) e.max = err, e.max_at_Hz = at_Hz;
  }

  QualityVerdict verdict(const std::string& law) const {
    const detail::QualityThresholds th;
    QualityVerdict v;
    std::set<double> isotherms, missed;
    int worst = -1;
    for (const auto& [key, e] : errors_) {
      ErrorFigures f;
      std::ostringstream g;
      g << "T=" << std::round(10.0 * key.first) / 10.0 << " degC measured, card's law";
      f.group = g.str();
      f.modulus = kModulusNames[key.second];
      f.count = e.count;
      f.mean_rel_error = e.sum / e.count;
      f.max_rel_error = e.max;
      f.max_at_frequency_Hz = e.max_at_Hz;
      isotherms.insert(key.first);
      const bool loss = key.second == 1;
      if (f.mean_rel_error > (loss ? th.loss_mean : th.storage_mean) ||
          f.max_rel_error > (loss ? th.loss_max : th.storage_max)) {
        missed.insert(key.first);
        if (worst < 0 || f.max_rel_error > v.figures[worst].max_rel_error) worst = static_cast<int>(v.figures.size());
      }
      v.figures.push_back(f);
    }
    if (worst < 0) return v;
    const ErrorFigures& w = v.figures[worst];
    std::ostringstream s;
    s.precision(3);
    s << "with its " << law << " law the card misses " << missed.size() << " of " << isotherms.size()
      << " measured isotherms; worst " << w.group.substr(0, w.group.find(" measured")) << ": " << w.modulus
      << " mean relative error " << 100.0 * w.mean_rel_error << " %, max " << 100.0 * w.max_rel_error << " % at ";
    // A relaxation row's place is its time (stored as 1/(2π t), relaxation_checks.cpp's convention).
    if (w.modulus == kModulusNames[2]) s << "t = " << 1.0 / (2.0 * core::kPi * w.max_at_frequency_Hz) << " s";
    else s << w.max_at_frequency_Hz << " Hz";
    s << " (the figures above are on the shifted table; at other temperatures the card answers through its law)";
    v.warnings.push_back(s.str());
    return v;
  }

 private:
  double isotherm(double T) {
    for (double t : seen_)
      if (std::abs(t - T) < detail::kSameTemperature_C) return t;
    seen_.push_back(T);
    return T;
  }
  std::vector<double> seen_;
  std::map<std::pair<double, int>, Errors> errors_;
};

}  // namespace

QualityVerdict measured_isotherm_verdict(const model::Model& model, const std::vector<double>& p,
                                         const data::DynamicTestTable& measured) {
  IsothermErrors errors;
  for (const auto& row : measured.rows) {
    const auto m = model.moduli(p.data(), row.condition);
    errors.add(row.condition.temperature_C, 0, m.storage, row.storage_MPa, row.condition.frequency_Hz);
    if (row.loss_MPa > Problem::kLossFloor * row.storage_MPa)
      errors.add(row.condition.temperature_C, 1, m.loss, row.loss_MPa, row.condition.frequency_Hz);
  }
  return errors.verdict(model::to_string(model.temperature_law_info().law));
}

QualityVerdict measured_isotherm_verdict(const model::Model& model, const std::vector<double>& p,
                                         const data::RelaxationTable& measured) {
  IsothermErrors errors;
  for (const auto& row : measured.rows) {
    model::TestCondition c;
    c.mode = row.mode;
    c.temperature_C = row.temperature_C;
    errors.add(row.temperature_C, 2, model.relaxation_modulus(p.data(), c, row.time_s), row.modulus_MPa,
               1.0 / (2.0 * core::kPi * row.time_s));
  }
  return errors.verdict(model::to_string(model.temperature_law_info().law));
}

}  // namespace fitlib::fit
