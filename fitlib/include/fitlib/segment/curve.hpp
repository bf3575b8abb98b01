#pragma once
// The parametric curve of the segment's neutral layer (cord line), docs/segment.md, "Parametric curve",
// Report I Eqs 5.10–5.20 with the corrected 5.19. The curve is built from the origin outward:
// its midpoint stays at the origin with zero tangent angle. Each side has n intervals of equal
// deformed length Δs with constant curvature K_i; the strain varies linearly between the
// interval ends, so 1/(1 + ε) is interpolated linearly in s (the assumption behind 5.19).
// A positive curvature bends towards −y (the rubber side, the pulley's centre).
#include <vector>

namespace fitlib::segment {

struct CurvePoint {
  double x_mm = 0.0, y_mm = 0.0;
  double phi_rad = 0.0;  // tangent angle, dx/ds = cos φ, dy/ds = −sin φ
  double K_1_mm = 0.0;   // curvature of the interval the point lies in
  double strain = 0.0;   // ε there (1/(1 + ε) linear within the interval)
};

// Where a point lies relative to the curve: path position s of its foot, tangent angle there and
// the distance h below the curve (positive on the rubber side).
struct CurveCoordinates {
  double phi_rad = 0.0, s_mm = 0.0, h_mm = 0.0;
};

class NeutralCurve {
 public:
  // Uniform curvature and strain on both sides, n intervals per side of deformed length ds_mm.
  static NeutralCurve uniform(double curvature_1_mm, double strain, double half_length_mm, int n = 8);
  // curvature_1_mm[i] on interval i of the positive side (i = 0 next to the origin), strain_end[i]
  // at the interval ends (n + 1 values, strain_end[0] at the origin); the negative side mirrors
  // the given negative-side arrays the same way.
  NeutralCurve(double ds_mm, std::vector<double> curvature_pos, std::vector<double> strain_pos,
               std::vector<double> curvature_neg, std::vector<double> strain_neg);

  CurvePoint at(double s_mm) const;                     // deformed path position, signed
  double s_from_unstrained(double s_org_mm) const;      // corrected 5.19, signed
  double unstrained_from_s(double s_mm) const;          // 5.17–5.20, signed
  CurveCoordinates coordinates(double x_mm, double y_mm) const;  // inverse map 5.10–5.15
  double reach_mm() const { return ds_ * static_cast<double>(k_pos_.size()); }

 private:
  CurvePoint walk(double s_abs, bool positive) const;
  double ds_;
  std::vector<double> k_pos_, eps_pos_, k_neg_, eps_neg_;
};

}  // namespace fitlib::segment
