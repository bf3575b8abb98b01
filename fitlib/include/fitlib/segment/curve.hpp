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
  double K_1_mm = 0.0;  // curvature of the interval the foot lies in
};

// The start points of a curve's intervals (NeutralCurve::starts), walked once: the inverse map of
// many points on one curve (the flank foundation's, segment/flank.hpp) needs no walk per point.
struct CurveStarts {
  std::vector<CurvePoint> positive, negative;
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
  // The same map for many points on one curve: the interval starts walked once (starts()), and the
  // interval of the foot's expected path position s_hint_mm taken when it holds the foot, else its
  // neighbours', else the nearest of all (at an interval's end, where two hold it, the first found).
  CurveStarts starts() const;
  CurveCoordinates coordinates(double x_mm, double y_mm, const CurveStarts& starts, double s_hint_mm) const;
  double reach_mm() const { return ds_ * static_cast<double>(k_pos_.size()); }

 private:
  CurvePoint walk(double s_abs, bool positive) const;
  // The foot of (x, y) on interval i of one side, whose start is `start` (as walk gives it): taken
  // into `best` when it lies within the interval and nearer than |best|'s depth `best_h`.
  void foot(std::size_t i, bool positive, CurvePoint start, double x_mm, double y_mm, CurveCoordinates& best,
            double& best_h) const;
  double ds_;
  std::vector<double> k_pos_, eps_pos_, k_neg_, eps_neg_;
};

}  // namespace fitlib::segment
