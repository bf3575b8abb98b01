#pragma once
// Drive geometry and tensions (Report I §4; docs/belt.md, "Equations as implemented").
//
// Pulleys are listed in the order the belt travels; the belt wraps every pulley on the outside of
// a convex path (an open drive), travelling counter-clockwise. Two-pulley drives are placed on the
// x axis from a centre distance. Lengths mm, forces N, angles rad, speeds mm/s.
#include <string>
#include <vector>

#include "fitlib/belt/contact_arc.hpp"

namespace fitlib::belt {

struct Pulley {
  std::string name;
  double pitch_radius_mm = 50.0;
  PulleyRole role = PulleyRole::driven;
  double x_mm = 0.0, y_mm = 0.0;  // centre
  double torque_Nm = 0.0;         // driven pulleys: load torque (0 = share of the remainder)
};

struct Span {  // from pulley i to pulley i+1 (mod n)
  double length_mm = 0.0;          // tangent length
  double center_distance_mm = 0.0;  // a between the two centres
};

struct DriveGeometry {
  std::vector<Pulley> pulleys;
  std::vector<double> wrap_rad;  // per pulley
  std::vector<Span> spans;       // spans[i] leaves pulley i
  double belt_length_mm = 0.0;   // pitch length
};

// Computes wrap angles and spans. InputError (key `drive.pulleys[i]...` or
// `drive.center_distance_mm`) for overlapping pulleys, a pulley the belt does not touch (order not
// counter-clockwise around a convex path), fewer than two pulleys, non-positive radii.
DriveGeometry make_geometry(std::vector<Pulley> pulleys, double belt_height_mm = 0.0);
// Two pulleys on the x axis, driver first.
DriveGeometry make_two_pulley_geometry(const Pulley& driver, const Pulley& driven,
                                       double center_distance_mm, double belt_height_mm = 0.0);

// Tensioning rule for the span that leaves the driver (the slack side).
enum class TensionRule { slack, tight, initial };
struct TensionInput {
  double driver_torque_Nm = 0.0;  // from torque or power/ω
  TensionRule rule = TensionRule::slack;
  double tension_N = 0.0;  // value of the rule's tension
};

// The scene key that gives the rule's tension ("drive.slack_tension_N", …), for messages.
const char* tension_key(TensionRule rule);

// Span tensions F_i (N) of the spans leaving each pulley, static (without centrifugal tension).
// Driven pulleys with torque_Nm > 0 take F difference torque/R; the others share the rest of the
// driver's force difference equally; idlers take none. InputError for a negative span tension
// (key drive.slack_tension_N / initial_tension_N / tight_tension_N) or driven torques that exceed
// the driver's.
std::vector<double> span_tensions(const DriveGeometry& g, const TensionInput& t);

// Index of the (single) driver; InputError if there is none or more than one.
std::size_t driver_index(const DriveGeometry& g);

}  // namespace fitlib::belt
