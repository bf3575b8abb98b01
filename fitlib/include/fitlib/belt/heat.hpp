#pragma once
// The belt's own temperature from its heat build-up (docs/thermal.md): the heat sources of one
// load cycle — hysteresis of the rubber layers, friction of the sliding arcs — and a steady lumped
// heat balance of the belt: convection to the air (a flat plate in parallel flow at the belt's
// speed) and conduction to the pulleys over the wrap, iterated to a fixed point with the sources'
// dependence on the belt temperature. Units: W, W/K, °C, mm in the inputs.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "fitlib/belt/load_cycle.hpp"

namespace fitlib::belt {

// A rubber layer loaded cyclically at one strain amplitude: volume over the belt, loss modulus
// (E″ or G″ with the matching amplitude: engineering shear γ_a for G″).
struct HysteresisLayer {
  std::string name;
  double volume_mm3 = 0.0;
  double loss_modulus_MPa = 0.0;
  double strain_amplitude = 0.0;
};

// W = π E″ ε_a² per unit volume and cycle (Report V (4.25) times ρc/f), J per cycle of the layer.
double hysteresis_work_J(const HysteresisLayer& layer);
// Σ W over the layers times the load frequency (W per belt). At the complete level the segment's
// own dissipation scales it (BeltTemperature::segment_over_layers, docs/thermal.md §1).
double hysteresis_power_W(const std::vector<HysteresisLayer>& layers, double load_frequency_Hz);
// E″ of a loss angle δ: E′ tan δ from the storage modulus E′ (= |E*| sin δ from the absolute one);
// the layers' modulus where the scene has no card (docs/decisions.md "Report V's 0.28 °C/s").
double loss_modulus_of_storage_MPa(double storage_MPa, double loss_angle_deg);
// Report V (4.25): the adiabatic rate of rise π ε_a² E″ f/(c ρ), °C/s.
double adiabatic_heating_rate_C_s(double loss_modulus_MPa, double strain_amplitude, double frequency_Hz,
                                  double specific_heat_J_kgC, double density_kg_m3);

// Friction power of the sliding arcs: both flanks' normal force per length p H/cos β times the
// friction used μ_u and the sliding speed, integrated along the path (W per belt, all pulleys).
double friction_power_W(const LoadCycle& cycle, const BeltSection& belt);
double friction_power_W(const LoadCycle& cycle, const BeltSection& belt, int pulley);

// Dry air at the film temperature (Incropera & DeWitt, Fundamentals of Heat and Mass Transfer,
// Table A.4, 250–400 K, linear between the rows; clamped outside).
struct AirProperties {
  double conductivity_W_mK = 0.0, kinematic_viscosity_m2_s = 0.0, prandtl = 0.0;
};
AirProperties air_at(double film_temperature_C);

// Average coefficient of a flat plate of length L in parallel flow at speed V (Incropera & DeWitt
// (7.30) laminar, Re_L ≤ 5·10⁵: Nu = 0.664 Re^½ Pr^⅓; (7.38) mixed: Nu = (0.037 Re^0.8 − 871) Pr^⅓).
double flat_plate_convection_W_m2K(double speed_m_s, double length_m, const AirProperties& air);

// Coefficients of the balance; NaN = the documented default (docs/thermal.md §3).
struct ThermalOptions {
  double ambient_C = 20.0;
  double pulley_C = NAN;                  // default: the ambient
  double convection_W_m2K = NAN;          // default: flat_plate_convection at the mean span length
  double contact_W_m2K = NAN;             // default: contact penetration in series with the bulk path
  double rubber_conductivity_W_mK = 0.25; // filled rubber (docs/thermal.md §3)
  double specific_heat_J_kgC = 1670.0;    // Report V (L3999): 1.67 kJ/kg°C
  double pulley_effusivity = 13400.0;     // steel √(kρc), W s^½/(m² K) (k 50, ρ 7850, c 460)
  double friction_to_belt = NAN;          // default: Blok's partition e_rubber/(e_rubber + e_pulley)
  // The layers' loss angle where the scene has no card for them: Report V's example (L3999), 8°.
  double loss_angle_deg = 8.0;
  double max_temperature_C = 300.0;       // beyond it the iteration is a thermal runaway
  int max_iterations = 200;
  double tolerance_C = 1e-9;
};

// The balance's conductances to ambient (W/K) and how they were made.
struct HeatPaths {
  double air_area_m2 = 0.0, convection_W_m2K = 0.0, convection_W_K = 0.0;
  std::vector<double> contact_area_m2, contact_W_m2K, contact_W_K;  // per pulley
  double friction_to_belt = 0.0;
  double pulley_C = 0.0;
};
HeatPaths heat_paths(const DriveCase& drive, const ThermalOptions& options, double belt_temperature_C);

struct HeatSources {
  double hysteresis_W = 0.0, friction_W = 0.0;  // friction: all of it; the belt takes friction_to_belt
  std::vector<HysteresisLayer> layers;
};

struct BeltTemperature {
  double temperature_C = 0.0, ambient_C = 0.0;
  int iterations = 0;
  HeatSources sources;     // at the fixed point
  HeatPaths paths;
  double heat_in_W = 0.0;  // hysteresis + the belt's share of the friction
  double convection_W = 0.0, contact_W = 0.0;  // to the air, to the pulleys
  double balance_error = 0.0;  // |in − out| / in at the fixed point
  // The complete level (docs/thermal.md §1): the segment's dissipation over the layers' estimate,
  // carried between the segment runs by the layers' temperature dependence; sources.hysteresis_W
  // is the layers' estimate times it. 1 and 0 runs at the beam and elastic levels.
  double segment_over_layers = 1.0;
  int segment_runs = 0;
  double segment_hysteresis_W = 0.0;  // the stresses' own segment run at the fixed point's temperature
};

// The fixed point T = T_pulley/ambient + (heat in at T)/(conductances at T), with `sources(T)` the
// heat sources with the cards' moduli at T. NumericalError "thermal runaway" when the iterate
// passes max_temperature_C or does not settle within max_iterations.
BeltTemperature solve_belt_temperature(const DriveCase& drive, const ThermalOptions& options,
                                       const std::function<HeatSources(double temperature_C)>& sources);

}  // namespace fitlib::belt
