#pragma once
// The homogeneous deformations of quasi-static (hyperelastic) tests (docs/hyperelastic.md
// §"Test modes"): what a quasi-static table row imposes and what a hyperelastic law evaluates —
// the vocabulary data and model share, so it lives below both (docs/architecture.md).
#include <optional>
#include <string>

namespace fitlib::core {

// uniaxial     principal stretches (λ, λ^-1/2, λ^-1/2), the nominal stress P11
// equibiaxial  (λ, λ, λ^-2), P11 = P22
// planar       pure shear (λ, 1, 1/λ), P11
// simple_shear F = I + γ e1⊗e2, the shear stress P12 = σ12 at shear strain γ
// volumetric   hydrostatic (J^1/3, J^1/3, J^1/3), the pressure p = −σ_mean (> 0 in compression)
//              at volume ratio J
enum class DeformationMode { uniaxial, equibiaxial, planar, simple_shear, volumetric };

inline const char* to_string(DeformationMode mode) {
  switch (mode) {
    case DeformationMode::uniaxial: return "uniaxial";
    case DeformationMode::equibiaxial: return "equibiaxial";
    case DeformationMode::planar: return "planar";
    case DeformationMode::simple_shear: return "simple_shear";
    case DeformationMode::volumetric: return "volumetric";
  }
  return "?";
}

// The label of to_string, plus "pure_shear" for planar; nullopt otherwise.
inline std::optional<DeformationMode> deformation_mode_from_label(const std::string& text) {
  for (DeformationMode m : {DeformationMode::uniaxial, DeformationMode::equibiaxial, DeformationMode::planar,
                            DeformationMode::simple_shear, DeformationMode::volumetric})
    if (text == to_string(m)) return m;
  if (text == "pure_shear") return DeformationMode::planar;
  return std::nullopt;
}

constexpr const char* kDeformationModeLabels = "uniaxial, equibiaxial, planar (pure_shear), simple_shear or volumetric";

// The abscissa of a mode: stretch λ (uniaxial, equibiaxial, planar), shear strain γ, volume ratio J.
inline const char* abscissa_name(DeformationMode mode) {
  return mode == DeformationMode::simple_shear ? "shear_strain"
         : mode == DeformationMode::volumetric ? "volume_ratio"
                                               : "stretch";
}
// Its value in the undeformed state (1, 0, 1).
inline double undeformed_abscissa(DeformationMode mode) { return mode == DeformationMode::simple_shear ? 0.0 : 1.0; }

}  // namespace fitlib::core
