// The end faces as long-belt sections (fitlib/segment/end_faces.hpp).
#include "fitlib/segment/end_faces.hpp"

#include <algorithm>
#include <cmath>

namespace fitlib::segment {

double shear_modulus_MPa(const PlaneStrainLaw& law) {
  return law.respond(Matrix2::Identity()).A(1, 1);  // A(2i+J, 2k+L): ∂P_01/∂F_01
}

double axial_modulus_MPa(const PlaneStrainLaw& law) {
  const Tangent A = law.respond(Matrix2::Identity()).A;  // along x with σ_yy = 0, plane strain
  return A(0, 0) - A(0, 3) * A(3, 0) / A(3, 3);
}

LongBeltSection::LongBeltSection(const CogSection& s, double x_mm, const std::array<const PlaneStrainLaw*, 2>& laws) {
  const int columns = 400, rows = 400;
  const double p = s.cog_pitch_mm, dx = p / columns;
  step_mm_ = s.height_mm / rows;
  std::vector<double> bottom(columns);  // depth of the profile across the pitch (midpoints)
  for (int i = 0; i < columns; ++i) bottom[i] = -s.bottom_y_mm(x_mm - 0.5 * p + (i + 0.5) * dx);
  const double G[2] = {shear_modulus_MPa(*laws[0]), shear_modulus_MPa(*laws[1])};
  const double E[2] = {axial_modulus_MPa(*laws[0]), axial_modulus_MPa(*laws[1])};
  auto role = [&](double h) { return h < s.cushion_mm ? 1 : 0; };
  // Loads below depth h per unit b, ε', K': the rubber area, ∫ E' w, −∫ E' h w (σ22 only in the
  // full-width layer above the land); built from the bottom up.
  std::vector<double> width(rows + 1);
  Profiles below;
  for (auto& v : below) v.assign(rows + 1, 0.0);
  for (int k = 0; k <= rows; ++k)
    for (double d : bottom) width[k] += d > k * step_mm_ ? dx / p : 0.0;
  for (int k = rows; k-- > 0;) {
    const double h = (k + 0.5) * step_mm_, w = 0.5 * (width[k] + width[k + 1]), layer = w > 0.999 ? 1.0 : 0.0;
    below[0][k] = below[0][k + 1] + w * step_mm_;
    below[1][k] = below[1][k + 1] + layer * E[role(h)] * step_mm_;
    below[2][k] = below[2][k + 1] - layer * E[role(h)] * h * step_mm_;
  }
  double axial = 0.0, warped_area = 0.0;
  for (int j = 0; j < 3; ++j) {
    shear_[j].assign(rows + 1, 0.0), warping_[j].assign(rows + 1, 0.0);
    for (int k = 0; k <= rows; ++k) {
      shear_[j][k] = width[k] > 0.0 ? -below[j][k] / width[k] : 0.0;
      if (k == 0) continue;
      const double h = (k - 0.5) * step_mm_;
      warping_[j][k] = warping_[j][k - 1] - 0.5 * (shear_[j][k - 1] + shear_[j][k]) * step_mm_ / G[role(h)];
      if (j == 0) axial += E[role(h)] * width[k] * step_mm_, warped_area += warping_[0][k] * width[k] * step_mm_;
    }
  }
  shear_lag_mm_ = std::sqrt(axial * warped_area) / below[0][0];  // sqrt(EA / (A_total / mean warping))
}

double LongBeltSection::combine(const Profiles& v, const SectionGradients& g, double depth_mm) const {
  const double u = std::clamp(depth_mm / step_mm_, 0.0, static_cast<double>(v[0].size() - 1));
  const std::size_t k = std::min(v[0].size() - 2, static_cast<std::size_t>(u));
  const double weight[3] = {g.body_N_mm3, g.strain_per_mm, g.curvature_per_mm2};
  double sum = 0.0;
  for (int j = 0; j < 3; ++j) sum += weight[j] * (v[j][k] + (u - k) * (v[j][k + 1] - v[j][k]));
  return sum;
}

std::vector<double> shear_lag_smoothed(const std::vector<double>& f, double ds_mm, double lag_mm) {
  const std::size_t M = f.size();
  const double a = std::exp(-ds_mm / lag_mm), norm = (1.0 - a) / (1.0 + a), wrap = 1.0 - std::pow(a, M);
  // One-sided sums Σ_k a^k f[i ∓ k] over the periodic samples; each pass starts from the periodic
  // value at its first sample (one period's sum over 1 − a^M).
  double forward = 0.0, backward = 0.0;
  for (std::size_t i = 0; i < M; ++i) forward = f[i] + a * forward, backward = f[M - 1 - i] + a * backward;
  forward /= wrap, backward /= wrap;
  std::vector<double> out(M), back(M);
  for (std::size_t i = M; i-- > 0;) back[i] = backward = f[i] + a * backward;
  for (std::size_t i = 0; i < M; ++i) {
    forward = f[i] + a * forward;
    out[i] = norm * (forward + back[i] - f[i]);
  }
  return out;
}

}  // namespace fitlib::segment
