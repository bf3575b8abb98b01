#pragma once
// Static load cases of the segment (issue 11 item 3): a prescribed neutral-layer strain ε and
// curvature K (the cord-line nodes placed on the exact curve under finite strain, end faces kept
// on the radial line through the curve's end point and free to slide along it, as in an endless
// belt) and an optional uniform follower pressure on the bottom face. Reports stresses in the
// local frame of the curve at named points, the cord-line reactions, the section force at
// mid-length and the section stiffnesses c and EI of the rubber about the cord line.
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fitlib/model/material_point.hpp"
#include "fitlib/segment/curve.hpp"
#include "fitlib/segment/elastic.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/section.hpp"
#include "fitlib/segment/solver.hpp"

namespace fitlib::segment {

struct IsotropicElastic {
  double E_MPa = 10.0, nu = 0.4995;
};

struct NamedPoint {
  std::string name;
  double x_mm = 0.0, y_mm = 0.0;  // reference (unloaded, straight) section coordinates
};

// radial: end faces on the radial line through the cord line's end point, sliding along it (an
// endless belt, exact for uniform states); free; sheared (load cycle only): radial faces warped and
// sheared as a long belt's sections under the local friction (segment/end_faces.hpp).
enum class EndCondition { radial, free, sheared };

struct StaticSetup {
  CogSection section;
  MeshKnobs mesh;
  SolverKnobs solver;
  ElasticLaw law = ElasticLaw::hencky;
  std::array<IsotropicElastic, 2> materials{};  // by Role: bottom, cushion
  // By Role: when set, the role's material is this point through the material-point contract (a
  // card's elastic equivalent, segment::role_point) instead of materials[role] under `law`.
  std::array<model::MaterialPointPtr, 2> material_points{};
  EndCondition ends = EndCondition::radial;
  std::vector<NamedPoint> points;               // beside the two standard points
  bool stiffness = true;                        // also solve the two small cases for c and EI
};

struct StaticLoad {
  double strain = 0.0;
  double curvature_1_mm = 0.0;
  double pressure_MPa = 0.0;
};

struct PointStress {
  NamedPoint point;
  double sigma11_MPa = 0.0;  // radial (outward normal of the cord curve)
  double sigma22_MPa = 0.0;  // longitudinal (tangent of the cord curve)
  double sigma12_MPa = 0.0;
  double sigma33_MPa = 0.0;  // out of plane
  double principal_max_MPa = 0.0;  // largest of the three principal stresses
};

struct StaticResult {
  std::vector<PointStress> stresses;     // gap_bottom, mid_cushion, then the user points
  Eigen::Vector2d cord_reaction_N_mm = Eigen::Vector2d::Zero();  // sum over the cord-line nodes
  double cord_moment_N = 0.0;            // about the origin, Σ y f_x − x f_y (N·mm per mm)
  SectionForce mid_section;              // through x = 0, about the cord point (origin)
  double c_N_per_mm = 0.0;               // ∂N/∂ε at zero load, per mm of width (0 if not asked)
  double EI_Nmm2_per_mm = 0.0;           // ∂M/∂K at zero load, per mm of width
  int elements = 0, nodes = 0, equations = 0, increments = 0, newton_iterations = 0;
  int assemblies = 0, residual_only_assemblies = 0;  // StaticSolution's
  double wall_s = 0.0;
};

// The standard monitored points: bottom of the central cog gap and mid-cushion at mid-length.
std::vector<NamedPoint> standard_points(const CogSection& section);

// The problem of a cord line placed on a curve that changes with λ: every cord-line node on the
// curve at its unstrained path position path_x_mm[node], the ends (radial) on the curve's normal
// through the end point. `mesh` is the reference (it may be bent, path_x the straight x).
// `end_shift_mm` (optional, radial ends): an end-face node's distance along the cord tangent from
// the radial line at λ (the face's warping), by node.
using EndShift = std::function<double(int node, double lambda)>;
StaticProblem cord_curve_problem(const Mesh& mesh, const std::vector<double>& path_x_mm,
                                 const std::array<const PlaneStrainLaw*, 2>& laws,
                                 std::function<NeutralCurve(double lambda)> curve_at, EndCondition ends,
                                 EndShift end_shift_mm = {});
// Its prescribed motion (prescribed_motion.cpp): constraints [0, n_top) the cord-line nodes on the
// curve, the rest end-face nodes on its normal through their column's cord point.
std::shared_ptr<const PrescribedMotion> cord_line(const Mesh& mesh, std::vector<NodeConstraint> constraints,
                                                  std::size_t n_top, std::vector<double> path_x_mm,
                                                  std::function<NeutralCurve(double lambda)> curve_at,
                                                  EndShift end_shift_mm);

// The problem of a load case on a mesh (constraints from the curve); laws must outlive it.
StaticProblem static_problem(const Mesh& mesh, const std::array<const PlaneStrainLaw*, 2>& laws,
                             const StaticLoad& load, EndCondition ends);

StaticResult run_static_case(const StaticSetup& setup, const StaticLoad& load, StaticSolution* solution = nullptr,
                             Mesh* mesh_out = nullptr);

}  // namespace fitlib::segment
