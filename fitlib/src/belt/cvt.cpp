#include "fitlib/belt/cvt.hpp"

#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::belt {
namespace {
using core::kPi;

void check(double wrap, double alpha, const CvtFormulary& c, const char* key) {
  if (!(alpha > 0.0 && alpha < kPi / 2))
    throw core::InputError("groove half-angle must lie in (0, 90) deg", {}, 0, 0, "cvt.groove_half_angle_deg");
  if (!(wrap > c.seat_rad + c.unseat_rad))
    throw core::InputError("wrap angle shorter than the seating and unseating regions (" +
                               core::format_number((c.seat_rad + c.unseat_rad) * 180 / kPi) + " deg)",
                           {}, 0, 0, key);
}
// Parabolic seating/unseating profile 1 − (u − 1)², u ∈ [0, 1].
double bump(double u) { return 1.0 - (u - 1.0) * (u - 1.0); }
}  // namespace

double driver_axial_thrust_density_N(double theta, double wrap, double T_T, double alpha,
                                     const CvtFormulary& c) {
  check(wrap, alpha, c, "cvt.driver_wrap_deg");
  const double base = T_T / (2.0 * c.xi_R * std::tan(alpha));
  if (theta < c.seat_rad) return base * bump(theta / c.seat_rad);
  if (theta > wrap - c.unseat_rad) return base * bump((wrap - theta) / c.unseat_rad);
  return base;
}

double driven_axial_thrust_density_N(double theta, double wrap, double T_T, double T_S,
                                     double alpha, const CvtFormulary& c) {
  check(wrap, alpha, c, "cvt.driven_wrap_deg");
  const double ta = std::tan(alpha);
  if (theta < c.seat_rad) return T_S / (2.0 * c.xi_N * ta) * bump(theta / c.seat_rad);
  if (theta > wrap - c.unseat_rad)
    return T_T / (2.0 * c.xi_N_unseat * ta) * bump((wrap - theta) / c.unseat_rad);
  // λ joins the inner power law to the unseating bump's height T_T/2 (λ of the paper).
  const double inner = wrap - c.seat_rad - c.unseat_rad;
  const double lambda = (0.5 * T_T - T_S / c.xi_N) / std::pow(inner, c.n);
  return T_S / (2.0 * c.xi_N * ta) + lambda / (2.0 * ta) * std::pow(theta - c.seat_rad, c.n);
}

double driver_axial_thrust_N(double T_T, double alpha, double wrap) {
  check(wrap, alpha, CvtFormulary{}, "cvt.driver_wrap_deg");
  return T_T / (4.4 * std::tan(alpha)) * (wrap - 2.0 * kPi / 27.0);
}

double driven_axial_thrust_N(double T_T, double T_S, double alpha, double wrap) {
  check(wrap, alpha, CvtFormulary{}, "cvt.driven_wrap_deg");
  const double ta = std::tan(alpha);
  return T_S / (3.0 * ta) * (wrap - kPi / 9.0) + kPi * T_T / (108.0 * ta) +
         (3.0 * T_T - 4.0 * T_S) / (72.0 * ta) * (wrap - 2.0 * kPi / 9.0);
}

}  // namespace fitlib::belt
