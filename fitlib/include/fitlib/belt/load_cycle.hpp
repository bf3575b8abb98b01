#pragma once
// The belt's load cycle around a drive (Report I §4; docs/belt.md, "Equations as implemented"):
// for every point of the belt path the belt force F, curvature K, side pressure p, sliding angle γ, sliding speed
// and friction utilisation, zone by zone (free span, entrance, non-sliding, sliding, exit, free
// span) for each pulley. The cycle starts at the middle of the span that leaves the driver (the
// slack side) and follows the belt.
#include <string>
#include <vector>

#include "fitlib/belt/drive.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::belt {

// Cross-section and stiffnesses the global mechanics needs.
struct BeltSection {
  double height_mm = 6.5862;          // H (mean height, Eq 6.2)
  double width_mm = 11.1542;          // B (mean width, Eq 6.3)
  double area_mm2 = 6.5862 * 11.1542;  // A for the centrifugal tension (4.53)
  double density_kg_m3 = 1200.0;
  double wedge_half_angle_rad = 19.0 * core::kPi / 180.0;  // β
  double c_N = 44000.0;       // longitudinal stiffness F/ε (A.3)
  double k1_MPa = 450.0;      // radial spring stiffness (A.37)
  double EI_Nmm2 = 7500.0;    // bending stiffness
};

// Effects of the load cycle that can be switched on or off (the planner's refinements).
struct LoadCycleEffects {
  bool bending_zones = true;     // free-span curvature (4.9) and entrance/exit zones (4.19–4.49)
  bool inertia = true;           // centrifugal tension F_c = ρAV² (4.53)
  bool full_ode = false;         // sliding arcs by the ODE (A.15–A.24) instead of the closed forms
  bool driver_exit_ramp = true;  // cosine ramp of friction utilisation at the driver's exit
};

struct LoadCycleOptions {
  LoadCycleEffects effects;
  double step_mm = 2.0;        // sampling step along the path
  int min_samples_per_zone = 12;
  double exit_ramp_fraction = 0.2;  // share of the driver's exit zone the ramp takes ([UNCLEAR])
  double ode_tolerance = 1e-9;
};

struct DriveCase {
  DriveGeometry geometry;
  std::vector<double> span_tension_N;  // static tensions of spans leaving each pulley
  std::string tension_key = "drive.slack_tension_N";  // the scene key they come from (messages)
  BeltSection belt;
  double friction = 0.8;
  double belt_speed_mm_s = 0.0;  // V of the unloaded belt
};

enum class Zone { free_span_in = 1, entrance = 2, non_sliding = 3, sliding = 4, exit = 5, free_span_out = 6 };
const char* to_string(Zone z);

struct LoadSample {
  double s_mm = 0.0;  // path coordinate from the start of the cycle
  double t_s = 0.0;   // time a belt point needs to get there (s/V)
  int pulley = 0;     // index in DriveGeometry::pulleys
  Zone zone = Zone::free_span_in;
  double F_N = 0.0;          // belt force (includes F_c)
  double K_1_mm = 0.0;       // curvature of the neutral layer
  double p_MPa = 0.0;        // side pressure (0 off the pulley)
  double gamma_rad = 0.0;    // sliding angle (0 off the pulley)
  double slide_mm_s = 0.0;   // sliding speed of the belt flank on the pulley
  double friction_used = 0.0;  // μ times the friction utilisation (0 off the pulley)
};

struct PulleyCycle {
  std::string name;
  PulleyRole role = PulleyRole::driven;
  double wrap_rad = 0.0, radius_mm = 0.0;
  double F_in_N = 0.0, F_out_N = 0.0;
  double c0 = 0.0, gamma_prime_P = 0.0;
  double phi_C_in_rad = 0.0, phi_C_out_rad = 0.0, phi_E_in_rad = 0.0, phi_E_out_rad = 0.0;
  double non_sliding_rad = 0.0, sliding_rad = 0.0;
  double sliding_closed_form_rad = -1.0;  // φ_S by the closed form (−1: out of its range)
  double sliding_ode_rad = -1.0;          // φ_S by the ODE (−1: not computed)
  std::string arc_method;                 // "closed-form", "ode", "ode (closed form out of range)"
  double capstan_limit = 0.0;             // exp(μα/sin β)
  double s_start_mm = 0.0, s_Cin_mm = 0.0, s_Ein_mm = 0.0, s_NS_mm = 0.0, s_Eout_mm = 0.0,
         s_Cout_mm = 0.0, s_end_mm = 0.0;
};

struct LoadCycle {
  std::vector<LoadSample> samples;
  std::vector<PulleyCycle> pulleys;  // in cycle order
  double centrifugal_tension_N = 0.0;
  double cycle_length_mm = 0.0, cycle_time_s = 0.0;
};

// Computes the load cycle. InputError (naming the key) when the drive cannot work: the belt
// slips (the needed sliding arc exceeds the contact arc), a span force not above the centrifugal
// tension (the belt lifts off), zones longer than the wrap.
LoadCycle compute_load_cycle(const DriveCase& drive, const LoadCycleOptions& options = {});

// Side pressure from radial equilibrium (A.2): p = F cos β /(2 H R (sin β − μ cos β_s cos γ)).
double side_pressure_MPa(double effective_force_N, double radius_mm, const BeltSection& belt,
                         double friction, double gamma_rad);

// Axial thrust on one pulley (both flanks' axial components, N): the axial force per unit length
// (pH/cos β)(cos β + μ sin β_s) of (A.4) integrated over the pulley's contact zones along s.
// The 1-D counterpart of Sorge's CVT formulary (cvt.hpp).
double axial_thrust_N(const LoadCycle& cycle, const BeltSection& belt, int pulley);

// Entrance/exit polynomial constants (4.21–4.39).
struct ZoneConstants {
  static constexpr double A1_in = 2.6613038, A2_in = -2.3055004;
  static constexpr double A1_out = 0.1666103, A2_out = 1.8107287;
  static constexpr double K0C_in = 1.0 / 2.048770, K0C_out = 1.0 / 5.203121;
  static constexpr double EI0_ref = 0.000015, F0_in_ref = 0.000574488, F0_out_ref = 0.001123726;
  static constexpr double theta_E_in = -0.000418;
};

}  // namespace fitlib::belt
