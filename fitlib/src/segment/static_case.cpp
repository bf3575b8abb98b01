#include "fitlib/segment/static_case.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "fitlib/core/error.hpp"
#include "fitlib/segment/curve.hpp"
#include "fitlib/segment/point_law.hpp"

namespace fitlib::segment {

std::vector<NamedPoint> standard_points(const CogSection& s) {
  return {{"gap_bottom", 0.0, s.bottom_y_mm(0.0)}, {"mid_cushion", 0.0, -0.5 * s.cushion_mm}};
}

StaticProblem cord_curve_problem(const Mesh& m, const std::vector<double>& path_x_mm,
                                 const std::array<const PlaneStrainLaw*, 2>& laws,
                                 std::function<NeutralCurve(double lambda)> curve_at, EndCondition ends,
                                 EndShift end_shift_mm) {
  StaticProblem p;
  p.mesh = &m;
  p.laws = laws;
  for (int n : m.top_nodes) p.constraints.push_back({n, 0.0, {true, true}});
  const std::size_t n_top = p.constraints.size();
  if (ends != EndCondition::free)  // radial (sheared adds the cycle's warping through end_shift_mm)
    for (const auto* side : {&m.left_nodes, &m.right_nodes})
      for (int n : *side)
        if (n != m.top_nodes.front() && n != m.top_nodes.back()) p.constraints.push_back({n, 0.0, {true, false}});
  // Bases at full load (the CalculiX deck uses them); the solver turns them with λ (PrescribedMotion::angles).
  const NeutralCurve full = curve_at(1.0);
  for (std::size_t c = n_top; c < p.constraints.size(); ++c)
    p.constraints[c].angle_rad = -full.at(full.s_from_unstrained(path_x_mm[p.constraints[c].node])).phi_rad;  // e0 = tangent
  p.motion = cord_line(m, p.constraints, n_top, path_x_mm, std::move(curve_at), std::move(end_shift_mm));
  return p;
}

StaticProblem static_problem(const Mesh& m, const std::array<const PlaneStrainLaw*, 2>& laws,
                             const StaticLoad& load, EndCondition ends) {
  std::vector<double> path_x;
  for (const Eigen::Vector2d& X : m.X) path_x.push_back(X.x());
  const double L = m.half_length_mm;
  StaticProblem p = cord_curve_problem(m, path_x, laws, [load, L](double lambda) {
    return NeutralCurve::uniform(lambda * load.curvature_1_mm, lambda * load.strain, 1.5 * L);
  }, ends);
  if (load.pressure_MPa != 0.0) p.loads.push_back(std::make_shared<FollowerPressure>(m, load.pressure_MPa));
  return p;
}

namespace {

PointStress local_stress(const Mesh& m, const StaticSolution& s, const NamedPoint& pt, const NeutralCurve& curve,
                         Integration integration) {
  double s33 = 0.0;
  const Eigen::Matrix2d sigma = stress_at(m, s, Eigen::Vector2d(pt.x_mm, pt.y_mm), integration, &s33);
  const double phi = curve.at(curve.s_from_unstrained(pt.x_mm)).phi_rad;
  const Eigen::Vector2d t(std::cos(phi), -std::sin(phi)), n(std::sin(phi), std::cos(phi));
  PointStress r;
  r.point = pt;
  r.sigma11_MPa = n.dot(sigma * n);
  r.sigma22_MPa = t.dot(sigma * t);
  r.sigma12_MPa = n.dot(sigma * t);
  r.sigma33_MPa = s33;
  const Eigen::Vector2d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(sigma).eigenvalues();
  r.principal_max_MPa = std::max(ev.maxCoeff(), s33);
  return r;
}

// A rubber surface under plane-strain compression creases below a stretch of about 0.65
// (neo-Hookean; Biot's instability 0.544). A tight bend compresses the gaps' land first, and the
// load path folds there (docs/segment.md "Static load cases": the reference section near 18 mm).
constexpr double kCreaseHintStretch = 0.85;

StaticSolution solve_bend(const StaticProblem& p, const StaticSetup& setup, const StaticLoad& load) {
  try {
    return solve_static(p, setup.solver);
  } catch (const core::NumericalError& e) {
    const double depth = -setup.section.land_y_mm();
    const double stretch = (1.0 + load.strain) * (1.0 - depth * load.curvature_1_mm);
    if (load.curvature_1_mm <= 0.0 || stretch > kCreaseHintStretch) throw;
    throw core::NumericalError(std::string(e.what()) + ". The bend to radius " +
                               core::short_number(1.0 / load.curvature_1_mm) + " mm compresses the gaps' land, " +
                               core::short_number(depth) + " mm below the cord line, to a nominal stretch of about " +
                               core::short_number(stretch) +
                               ": a rubber surface creases below about 0.65 in plane strain (Biot's instability "
                               "0.544), where the load path folds; a larger radius passes (docs/segment.md \"Static "
                               "load cases\")");
  }
}

}  // namespace

StaticResult run_static_case(const StaticSetup& setup, const StaticLoad& load, StaticSolution* solution_out,
                             Mesh* mesh_out) {
  const auto t0 = std::chrono::steady_clock::now();
  const Mesh m = build_mesh(setup.section, setup.mesh);
  std::array<std::unique_ptr<PlaneStrainLaw>, 2> owned;
  for (int k = 0; k < 2; ++k)
    owned[k] = setup.material_points[k]
                   ? std::make_unique<ContractLaw>(setup.material_points[k])
                   : make_elastic(setup.law, setup.materials[k].E_MPa, setup.materials[k].nu);
  const std::array<const PlaneStrainLaw*, 2> laws{owned[0].get(), owned[1].get()};
  const Eigen::Vector2d origin = Eigen::Vector2d::Zero();

  const StaticProblem p = static_problem(m, laws, load, setup.ends);
  const StaticSolution s = solve_bend(p, setup, load);
  StaticResult r;
  const NeutralCurve curve = NeutralCurve::uniform(load.curvature_1_mm, load.strain, 1.5 * m.half_length_mm);
  std::vector<NamedPoint> points = standard_points(setup.section);
  points.insert(points.end(), setup.points.begin(), setup.points.end());
  for (const auto& pt : points) r.stresses.push_back(local_stress(m, s, pt, curve, setup.solver.physics.integration));
  for (int n : m.top_nodes) {
    const Eigen::Vector2d f = s.reaction_N_mm[n], x = m.X[n] + s.u_mm[n];
    r.cord_reaction_N_mm += f;
    r.cord_moment_N += x.y() * f.x() - x.x() * f.y();
  }
  r.mid_section = section_force(p, s, 0.0, origin, setup.solver.physics.integration);
  if (setup.stiffness) {  // small cases from the unloaded state: secants there are the tangents
    SolverKnobs one = setup.solver;
    one.stepping.steps = 1;
    const double eps = 1e-5, K = 1e-6;
    const StaticProblem ps = static_problem(m, laws, {eps, 0.0, 0.0}, setup.ends);
    r.c_N_per_mm = section_force(ps, solve_static(ps, one), 0.0, origin, one.physics.integration).force_N_mm.x() / eps;
    const StaticProblem pb = static_problem(m, laws, {0.0, K, 0.0}, setup.ends);
    r.EI_Nmm2_per_mm = section_force(pb, solve_static(pb, one), 0.0, origin, one.physics.integration).moment_N / K;
  }
  r.elements = m.element_count();
  r.nodes = m.node_count();
  r.equations = s.equations;
  r.increments = s.increments;
  r.newton_iterations = s.newton_iterations;
  r.assemblies = s.assemblies, r.residual_only_assemblies = s.residual_only_assemblies;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (solution_out) *solution_out = s;
  if (mesh_out) *mesh_out = m;
  return r;
}

}  // namespace fitlib::segment
