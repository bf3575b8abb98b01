#include "fitlib/belt/drive.hpp"

#include <cmath>
#include <string>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::belt {
namespace {
using core::InputError;
using core::kPi;

std::string pulley_key(std::size_t i, const char* field) {
  return "drive.pulleys[" + std::to_string(i) + "]." + field;
}
}  // namespace

DriveGeometry make_geometry(std::vector<Pulley> pulleys, double belt_height_mm) {
  const std::size_t n = pulleys.size();
  if (n < 2) throw InputError("a drive needs at least two pulleys", {}, 0, 0, "drive.pulleys");
  for (std::size_t i = 0; i < n; ++i)
    if (!(pulleys[i].pitch_radius_mm > 0.0) || !std::isfinite(pulleys[i].pitch_radius_mm))
      throw InputError("pitch diameter must be positive", {}, 0, 0,
                       pulley_key(i, "pitch_diameter_mm"));
  DriveGeometry g;
  g.pulleys = std::move(pulleys);
  const auto& p = g.pulleys;
  // Tangent direction θ_i of the span leaving pulley i (belt on the outside, CCW travel):
  // d·n = r2 − r1 with n the left normal of the span, so θ = ψ − asin((r2 − r1)/|d|).
  std::vector<double> theta(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double dx = p[j].x_mm - p[i].x_mm, dy = p[j].y_mm - p[i].y_mm;
    const double a = std::hypot(dx, dy);
    const double r1 = p[i].pitch_radius_mm, r2 = p[j].pitch_radius_mm;
    // Outer flanks must clear each other: pitch radius plus the belt below the pitch line.
    if (a <= r1 + r2 + belt_height_mm)
      throw InputError("pulleys '" + p[i].name + "' and '" + p[j].name + "' overlap (centre distance " +
                           core::format_number(a) + " mm <= sum of radii " + core::format_number(r1 + r2) + " mm)",
                       {}, 0, 0, n == 2 ? "drive.center_distance_mm" : pulley_key(j, "center_mm"));
    theta[i] = std::atan2(dy, dx) - std::asin((r2 - r1) / a);
    g.spans.push_back({std::sqrt(a * a - (r2 - r1) * (r2 - r1)), a});
  }
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t prev = (i + n - 1) % n;
    double wrap = std::remainder(theta[i] - theta[prev], 2.0 * kPi);  // in (−π, π]
    if (n == 2 && std::abs(wrap) < 1e-12) wrap = kPi;
    if (wrap < 0.0) wrap += 2.0 * kPi;
    if (!(wrap > 1e-9))
      throw InputError("the belt does not wrap pulley '" + p[i].name +
                           "': list pulleys in counter-clockwise travel order around a convex path",
                       {}, 0, 0, pulley_key(i, "center_mm"));
    g.wrap_rad.push_back(wrap);
    total += wrap;
  }
  if (std::abs(total - 2.0 * kPi) > 1e-6)
    throw InputError("pulleys do not form a convex open drive (wrap angles sum to " +
                         core::format_number(total * 180.0 / kPi) + " deg, not 360): list them in " +
                         (std::abs(total - 4.0 * kPi) < 1e-6 ? "counter-clockwise travel order (they are clockwise)"
                                                             : "counter-clockwise travel order around a convex path"),
                     {}, 0, 0, "drive.pulleys");
  g.belt_length_mm = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    g.belt_length_mm += g.spans[i].length_mm + g.wrap_rad[i] * p[i].pitch_radius_mm;
  return g;
}

DriveGeometry make_two_pulley_geometry(const Pulley& driver, const Pulley& driven,
                                       double center_distance_mm, double belt_height_mm) {
  if (!(center_distance_mm > 0.0))
    throw InputError("centre distance must be positive", {}, 0, 0, "drive.center_distance_mm");
  Pulley a = driver, b = driven;
  a.x_mm = a.y_mm = 0.0;
  b.x_mm = center_distance_mm;
  b.y_mm = 0.0;
  return make_geometry({a, b}, belt_height_mm);
}

std::size_t driver_index(const DriveGeometry& g) {
  std::size_t found = g.pulleys.size();
  for (std::size_t i = 0; i < g.pulleys.size(); ++i) {
    if (g.pulleys[i].role != PulleyRole::driver) continue;
    if (found != g.pulleys.size())
      throw InputError("more than one driver pulley", {}, 0, 0, "drive.pulleys");
    found = i;
  }
  if (found == g.pulleys.size())
    throw InputError("no pulley has role = \"driver\"", {}, 0, 0, "drive.pulleys");
  return found;
}

const char* tension_key(TensionRule rule) {
  switch (rule) {
    case TensionRule::tight: return "drive.tight_tension_N";
    case TensionRule::initial: return "drive.initial_tension_N";
    case TensionRule::slack: break;
  }
  return "drive.slack_tension_N";
}

std::vector<double> span_tensions(const DriveGeometry& g, const TensionInput& t) {
  const std::size_t n = g.pulleys.size();
  const std::size_t d = driver_index(g);
  const double total_dF = t.driver_torque_Nm * 1000.0 / g.pulleys[d].pitch_radius_mm;
  if (!(total_dF >= 0.0) || !std::isfinite(total_dF))
    throw InputError("driver torque must be finite and >= 0", {}, 0, 0, "drive.torque_Nm");
  // Force rise over each pulley: driven pulleys raise the tension, the driver drops it.
  std::vector<double> rise(n, 0.0);
  double assigned = 0.0;
  std::size_t sharing = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Pulley& p = g.pulleys[i];
    if (p.role != PulleyRole::driven) continue;
    if (p.torque_Nm > 0.0) {
      rise[i] = p.torque_Nm * 1000.0 / p.pitch_radius_mm;
      assigned += rise[i];
    } else {
      ++sharing;
    }
  }
  if (assigned > total_dF * (1.0 + 1e-12))
    throw InputError("driven torques need more force difference than the driver supplies", {}, 0, 0,
                     "drive.pulleys");
  if (sharing == 0 && std::abs(assigned - total_dF) > 1e-9 * std::max(1.0, total_dF))
    throw InputError("driven torques do not balance the driver torque", {}, 0, 0, "drive.torque_Nm");
  for (std::size_t i = 0; i < n; ++i)
    if (g.pulleys[i].role == PulleyRole::driven && !(g.pulleys[i].torque_Nm > 0.0))
      rise[i] = (total_dF - assigned) / static_cast<double>(sharing);
  rise[d] = -total_dF;
  double slack = 0.0;
  switch (t.rule) {
    case TensionRule::slack: slack = t.tension_N; break;
    case TensionRule::tight: slack = t.tension_N - total_dF; break;
    case TensionRule::initial: slack = t.tension_N - 0.5 * total_dF; break;
  }
  if (!(slack >= 0.0) || !std::isfinite(slack))
    throw InputError("slack-side tension would be negative (" + core::format_number(slack, 4) +
                         " N): raise the tension or lower the torque",
                     {}, 0, 0, tension_key(t.rule));
  std::vector<double> F(n);
  double f = slack;
  for (std::size_t k = 1; k <= n; ++k) {  // walk from the driver's outgoing span
    const std::size_t i = (d + k) % n;
    f += rise[i];
    F[i] = f;
  }
  F[d] = slack;
  return F;
}

}  // namespace fitlib::belt
