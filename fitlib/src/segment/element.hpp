#pragma once
// Isoparametric quadrilaterals (4 or 8 nodes) for the total-Lagrangian plane-strain element and
// the bottom-face follower pressure (docs/segment.md §Element).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "fitlib/segment/elastic.hpp"

namespace fitlib::segment::detail {

struct GaussPoint {
  double xi, eta, weight;
};
// n × n Gauss–Legendre rule (n = 2 or 3).
std::vector<GaussPoint> gauss_rule(int n);
// 1-D Gauss abscissae of the n-point rule, ascending.
std::vector<double> gauss_abscissae(int n);

// Shape functions and their (ξ, η) derivatives; node order: corners counter-clockwise, midsides.
void shape(int nodes, double xi, double eta, double* N, double* dN_dxi, double* dN_deta);

using ElementVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 16, 1>;
using ElementMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 16, 16>;

struct ElementState {   // what the solver keeps per integration point after convergence
  Eigen::Matrix2d cauchy_MPa;
  double sigma33_MPa;
  Eigen::Vector2d X_mm;  // reference position
  Eigen::Matrix2d piola_MPa;
  Eigen::Matrix2d F;     // deformation gradient (in-plane)
};

// The element's block of integration-point states (law.state_size() doubles per point, in rule
// order) and the step they are updated over.
struct ElementStep {
  const double* state_n = nullptr;
  double* state_next = nullptr;
  double dt_s = 0.0;
  double temperature_C = 0.0;
};

// A rule point's shape functions N, ∂N/∂X and reference volume dV in one element (the reference
// configuration does not move, so an assembler computes them once per mesh); ok = false where the
// element's map is inverted there.
struct ReferencePoint {
  double N[8];
  Eigen::Matrix<double, 8, 2> G;
  double dV = 0.0;
  bool ok = false;
};
std::vector<ReferencePoint> reference_points(const std::vector<Eigen::Vector2d>& X, const std::vector<GaussPoint>& rule);

// Internal force and tangent of one element; false (with nothing written) when an integration
// point is inverted (J ≤ 0) or the law returns a non-finite stress. `f_bar`: the law sees
// F̄ = (J̄/J)^½ F, J̄ interpolated from the reduced points (docs/segment.md §Element choice); the
// states then hold F̄, its Cauchy stress and the effective first Piola stress P(F̄)/α.
// `memory` (NewtonOptions::linearised_pressure; not with F-bar): the tangent's pressure term at the
// pressure linearised over the step from the last tangent assembly's F at each point (read when
// `follows`, then overwritten). `reference`: this element's rule points (reference_points), else
// computed here.
struct PressureMemory {
  Eigen::Matrix2d* F_last = nullptr;  // one per point of the rule
  bool follows = false;
};
bool element_response(const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& u,
                      const PlaneStrainLaw& law, const std::vector<GaussPoint>& rule, const ElementStep& step,
                      ElementVector& f, ElementMatrix* K, std::vector<ElementState>* states, bool f_bar = false,
                      PressureMemory* memory = nullptr, const ReferencePoint* reference = nullptr);

// Internal force f_a = Σ P ∂N_a/∂X dV from given first Piola–Kirchhoff stresses at the points.
void internal_force(const std::vector<Eigen::Vector2d>& X, const std::vector<GaussPoint>& rule,
                    const std::vector<Eigen::Matrix2d>& piola_MPa, ElementVector& f);

// Follower pressure p on a 2- or 3-node edge (a → b, midside), pushing against the outward
// normal of the counter-clockwise element: external force and its derivative d f_ext / d u.
void pressure_load(const std::vector<Eigen::Vector2d>& x_current, double p_MPa, ElementVector& f_ext,
                   ElementMatrix& dfext_du);

}  // namespace fitlib::segment::detail
