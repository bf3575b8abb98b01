#pragma once
// The end faces of a short segment as sections of a long belt (docs/segment.md "End faces"). In a
// belt on a prescribed cord line, the rubber below depth h is held by the shear at h against the
// longitudinal body force b (friction, N/mm³) and the change along the belt of its longitudinal
// stress σ22 = E'(ε − K h) (the layer above the land; the cogs carry little), so a section carries
// (Jourawski, w the rubber width at h per pitch)
//   σ12(h) w(h) = −∫_h (b + ∂σ22/∂s) w dh' = −[b A(h) + ε' ∫_h E' w dh' − K' ∫_h E' h' w dh']
// and warps along the belt by u(h) = −∫_0^h σ12/G dh'. The radial end condition holds each face on
// its radial line (u = 0, σ12 = 0): the faces of a short segment then carry the friction near them
// instead of the cushion, and its mid-cushion shear comes out too low.
#include <array>
#include <vector>

#include "fitlib/segment/elastic.hpp"
#include "fitlib/segment/section.hpp"

namespace fitlib::segment {

// What a section's shear responds to: b (N/mm³), ε' = dε/ds (1/mm), K' = dK/ds (1/mm²).
struct SectionGradients {
  double body_N_mm3 = 0.0, strain_per_mm = 0.0, curvature_per_mm2 = 0.0;
};

class LongBeltSection {
 public:
  // The section at reference x_mm (its pitch centred there); laws by Role (bottom, cushion).
  LongBeltSection(const CogSection& section, double x_mm, const std::array<const PlaneStrainLaw*, 2>& laws);
  double shear_MPa(const SectionGradients& g, double depth_mm) const { return combine(shear_, g, depth_mm); }
  double warping_mm(const SectionGradients& g, double depth_mm) const { return combine(warping_, g, depth_mm); }
  // The shear-lag length ℓ = sqrt(EA/k): EA the rubber's axial stiffness per mm of width, k = A_total
  // over the mean warping per unit b (the shear connection to the cord per unit slip).
  double shear_lag_mm() const { return shear_lag_mm_; }

 private:
  using Profiles = std::array<std::vector<double>, 3>;  // per unit b, ε', K' on depths k·step
  double combine(const Profiles& v, const SectionGradients& g, double depth_mm) const;
  double step_mm_ = 0.0, shear_lag_mm_ = 0.0;
  Profiles shear_, warping_;
};

// The small-strain in-plane shear modulus of a law (∂P12/∂F12 at F = I, virgin state).
double shear_modulus_MPa(const PlaneStrainLaw& law);
// The small-strain plane-strain modulus along the belt with no radial stress (E/(1 − ν²) isotropic).
double axial_modulus_MPa(const PlaneStrainLaw& law);

// Samples (equally spaced, one period) smoothed along the belt by the shear-lag kernel
// e^(−|s|/ℓ)/(2ℓ): the response of a layer on a rigid cord to a longitudinal load,
// EA u'' − k u + f = 0.
std::vector<double> shear_lag_smoothed(const std::vector<double>& f, double ds_mm, double lag_mm);

}  // namespace fitlib::segment
