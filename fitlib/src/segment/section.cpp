#include "fitlib/segment/section.hpp"

#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::segment {
namespace {

struct Corner {  // a round of radius r between two lines meeting at V
  double cx, cy;        // centre
  double x_in, x_out;   // x of the tangent points on the first and second line
};

// Round tangent to two lines through V with unit directions d1 (away from V along the first
// line) and d2 (along the second); the centre lies on the bisector of the angle between them.
Corner round(double vx, double vy, double d1x, double d1y, double d2x, double d2y, double r) {
  const double cos_angle = d1x * d2x + d1y * d2y;
  const double half = 0.5 * std::acos(cos_angle);
  double bx = d1x + d2x, by = d1y + d2y;
  const double bn = std::hypot(bx, by);
  bx /= bn;
  by /= bn;
  const double to_centre = r / std::sin(half), to_tangent = r / std::tan(half);
  return {vx + bx * to_centre, vy + by * to_centre, vx + d1x * to_tangent, vx + d2x * to_tangent};
}

}  // namespace

double CogSection::bottom_y_mm(double x_mm) const {
  // Fold onto half a period measured from the gap centre.
  double u = std::fmod(std::abs(x_mm), cog_pitch_mm);
  if (u > 0.5 * cog_pitch_mm) u = cog_pitch_mm - u;
  const double a = flank_angle_deg * core::kPi / 180.0;
  const double fx = std::sin(a), fy = -std::cos(a);  // down the flank
  const double y_land = land_y_mm(), y_tip = -height_mm;
  const double x_root = land_half_width_mm, x_tipc = x_root + cog_depth_mm * std::tan(a);
  // Root fillet: in the gap, tangent to the land (towards −x) and the flank (down).
  const Corner f = round(x_root, y_land, -1.0, 0.0, fx, fy, root_fillet_mm);
  // Tip round: in the cog, tangent to the flank (up) and the tip (towards +x).
  const Corner t = round(x_tipc, y_tip, -fx, -fy, 1.0, 0.0, tip_radius_mm);
  auto arc = [](double cx, double cy, double r, double x, double side) {
    const double d = std::max(0.0, r * r - (x - cx) * (x - cx));
    return cy + side * std::sqrt(d);
  };
  if (u <= f.x_in) return y_land;
  if (u <= f.x_out) return arc(f.cx, f.cy, root_fillet_mm, u, +1.0);
  if (u <= t.x_in) return y_land + (u - x_root) * fy / fx;
  if (u <= t.x_out) return arc(t.cx, t.cy, tip_radius_mm, u, -1.0);
  return y_tip;
}

void CogSection::validate() const {
  auto bad = [](const char* key, const std::string& why) {
    throw core::InputError(why, "", 0, 0, std::string("belt.") + key);
  };
  if (!(height_mm > 0.0)) bad("height_mm", "section height must be positive");
  if (!(cushion_mm > 0.0)) bad("cushion_mm", "cushion thickness must be positive");
  if (!(cog_depth_mm >= 0.0) || cushion_mm >= height_mm - cog_depth_mm)
    bad("cog_depth_mm", "cog depth must leave bottom rubber between the cushion and the gap bottom");
  if (!(flank_angle_deg > 0.0 && flank_angle_deg < 60.0))
    bad("cog_flank_angle_deg", "flank angle from radial must lie in (0, 60) deg");
  const double a = flank_angle_deg * core::kPi / 180.0;
  const double half_angle = 0.5 * (0.5 * core::kPi + a);
  const double fillet_reach = root_fillet_mm / std::tan(half_angle);
  const double tip_reach = tip_radius_mm / std::tan(half_angle);
  auto mm = [](double v) { return core::format_number(v, 4) + " mm"; };
  if (!(root_fillet_mm >= 0.0) || land_half_width_mm - fillet_reach < 0.0)
    bad("cog_root_fillet_mm", "the root fillet of " + mm(root_fillet_mm) + " reaches " + mm(fillet_reach) +
                                  " along the land, whose half-width (cog_land_half_width_mm) is " +
                                  mm(land_half_width_mm) + ": reduce the fillet or widen the land");
  const double x_tip = land_half_width_mm + cog_depth_mm * std::tan(a);
  if (!(tip_radius_mm >= 0.0) || x_tip + tip_reach > 0.5 * cog_pitch_mm)
    bad("cog_tip_radius_mm", "the cog tip's corner lies " + mm(x_tip) + " from the gap centre and its round of " +
                                 mm(tip_radius_mm) + " reaches " + mm(tip_reach) + " beyond it, past half the pitch (" +
                                 mm(0.5 * cog_pitch_mm) + "): the cog does not fit in its pitch; increase cog_pitch_mm "
                                 "or reduce the tip round, the land half-width, the cog depth or the flank angle");
  if (fillet_reach + tip_reach > cog_depth_mm / std::cos(a))
    bad("cog_depth_mm", "the root fillet and the tip round need " + mm(fillet_reach + tip_reach) +
                            " of the flank, which is " + mm(cog_depth_mm / std::cos(a)) +
                            " long: deepen the cogs or reduce the rounds (the segment models cogged sections only)");
}

}  // namespace fitlib::segment
