#pragma once
// Stresses on a crack plane and the effective stress of Report I §6.4 (docs/fatigue.md §1).
//
// Plane coordinates: 1 radial (towards the cord line), 2 longitudinal (along the belt). A crack
// direction at angle θ from radial (positive towards +2) runs along t = (cos θ, sin θ); its plane
// normal is n = (−sin θ, cos θ). θ = 0 is the radial crack of mode 1; θ = 90° the longitudinal
// crack (separation) of mode 2, whose normal is radial.
namespace fitlib::fatigue {

struct PlaneStress {
  double s11_MPa = 0.0, s22_MPa = 0.0, s12_MPa = 0.0;
};

struct CrackPlaneStress {
  double normal_MPa = 0.0;  // σ = n·S·n
  double shear_MPa = 0.0;   // τ = t·S·n
};

CrackPlaneStress crack_plane_stress(const PlaneStress& s, double crack_angle_rad);

// σ_e = √(σ² + τ²) for σ ≥ 0, |τ| for σ < 0 (6.25–6.26): a closed crack feels only shear.
double effective_stress_MPa(const CrackPlaneStress& c);

// Worst σ_e over crack directions θ ∈ [−sweep, +sweep] from radial (exact: the maximum of the
// piecewise-smooth σ_e(θ) over the end points, the stationary points of both branches and the
// branch switches σ = 0). `worst_angle_rad` receives the maximising θ when not null.
double worst_radial_crack_stress_MPa(const PlaneStress& s, double sweep_rad,
                                     double* worst_angle_rad = nullptr);

// Mode 2: longitudinal crack, σ = σ11 and τ = σ12.
double separation_stress_MPa(const PlaneStress& s);

}  // namespace fitlib::fatigue
