#pragma once
// The longitudinal section of a cogged belt (docs/segment.md, "Mesh"): cord line at y = 0 as the
// top boundary, a cushion layer below it, the bottom rubber down to a cogged profile. Gap centres
// at x = 0, ±pitch, …; cog centres half a pitch away. The profile is a graph y(x): a land at the
// gap bottom, a root fillet, a straight flank at flank_angle from the radial direction, a tip
// round and the flat cog tip.
namespace fitlib::segment {

struct CogSection {
  double height_mm = 6.6;          // cord line to cog tip
  double cushion_mm = 0.5;         // material role `cushion`
  double cog_pitch_mm = 9.0;
  double cog_depth_mm = 2.5;       // land (gap bottom) to cog tip
  double flank_angle_deg = 20.0;   // from the radial direction
  double land_half_width_mm = 1.75;  // gap centre to the sharp land/flank corner
  double root_fillet_mm = 0.75;
  double tip_radius_mm = 0.5;

  double land_y_mm() const { return -(height_mm - cog_depth_mm); }
  // Bottom boundary y(x), periodic in the pitch, symmetric about each gap centre.
  double bottom_y_mm(double x_mm) const;
  // Throws core::InputError naming the belt key when the profile cannot be built.
  void validate() const;
};

}  // namespace fitlib::segment
