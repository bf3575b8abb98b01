// The observers of a load-cycle run (cycle_observers.hpp).
#include "cycle_observers.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace fitlib::segment::detail {

CycleSample local_sample(const IntegrationPointStress& ip, double phi) {
  const Eigen::Vector2d t(std::cos(phi), -std::sin(phi)), n(std::sin(phi), std::cos(phi));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(ip.F * ip.F.transpose());
  const Eigen::Matrix2d e = eig.eigenvectors() * (0.5 * eig.eigenvalues().array().log()).matrix().asDiagonal() *
                            eig.eigenvectors().transpose();
  CycleSample c;
  c.s11_MPa = n.dot(ip.cauchy_MPa * n), c.s22_MPa = t.dot(ip.cauchy_MPa * t), c.s12_MPa = n.dot(ip.cauchy_MPa * t);
  c.s33_MPa = ip.sigma33_MPa;
  c.e11 = n.dot(e * n), c.e22 = t.dot(e * t), c.e12 = n.dot(e * t);
  return c;
}

namespace {

// The increment's forces along the cord tangent at the middle: the cord line's reactions, the left
// end face's (without the cord node) and the rubber's section force through x = 0.
void longitudinal_loads(const StaticProblem& p, const StaticSolution& s, const NeutralCurve& curve, const Mesh& m,
                        const std::vector<double>& path_x, Integration integration, IncrementLoads& q) {
  const double phi = curve.at(curve.s_from_unstrained(0.0)).phi_rad;
  const Eigen::Vector2d t(std::cos(phi), -std::sin(phi));
  q.cord_longitudinal_N_mm = q.cord_reaction_N_mm.dot(t);
  for (int node : m.left_nodes)
    if (node != m.top_nodes.front()) q.left_end_longitudinal_N_mm += s.reaction_N_mm[node].dot(t);
  for (int node : m.top_nodes)
    if (m.X[node].x() < 0.0) q.left_cord_longitudinal_N_mm += s.reaction_N_mm[node].dot(t);
  for (std::size_t node = 0; node < s.inertia_N_mm.size(); ++node)  // PhysicsOptions::inertia
    if (path_x[node] < 0.0) q.left_inertia_longitudinal_N_mm += s.inertia_N_mm[node].dot(t);
  q.rubber_section_N_mm = section_force(p, s, 0.0, Eigen::Vector2d::Zero(), integration).force_N_mm.dot(t);
}

}  // namespace

PointMonitor::PointMonitor(const CycleFrame& frame, const Mesh& straight, double K_m,
                           const std::vector<NamedPoint>& named, int gauss_order, std::vector<MonitoredHistory>& out)
    : frame_(frame), order_(gauss_order), out_(out) {
  Mesh points = straight;  // each named point carried into the moulded reference as the nodes are
  points.X.clear();
  for (const NamedPoint& np : named) points.X.emplace_back(np.x_mm, np.y_mm);
  const Mesh moulded = wrapped(points, K_m);
  for (std::size_t k = 0; k < named.size(); ++k) {
    MonitoredHistory mh;
    mh.point = named[k];
    mh.X_mm = moulded.X[k];
    mh.at = locate(*frame.mesh, mh.X_mm);
    mh.role = frame.mesh->roles[mh.at.element];
    out_.push_back(mh);
  }
}

void PointMonitor::converged(double lambda, const StaticSolution& s) {
  const double tau = frame_.tau(lambda);
  const NeutralCurve& curve = frame_.curve(lambda);
  for (MonitoredHistory& mh : out_) {
    CycleSample c = local_sample(interpolate(s, mh.at, order_, mh.X_mm),
                                 curve.at(curve.s_from_unstrained(mh.point.x_mm)).phi_rad);
    c.t_s = tau * frame_.period_s;
    c.s_mm = frame_.s_mm(tau);
    mh.samples.push_back(c);
  }
}

ElementMeans::ElementMeans(const CycleFrame& frame, const Mesh& straight, std::vector<MonitoredHistory>& out)
    : frame_(frame), out_(out) {
  for (int e = 0; e < straight.element_count(); ++e) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (int a = 0; a < 4; ++a) centre += 0.25 * straight.X[straight.elements[e][a]];
    MonitoredHistory mh;
    mh.point = {"e" + std::to_string(e), centre.x(), centre.y()};
    mh.role = straight.roles[e];
    mh.at.element = e;
    out_.push_back(std::move(mh));
  }
}

void ElementMeans::converged(double lambda, const StaticSolution& s) {
  const double tau = frame_.tau(lambda);
  const NeutralCurve& curve = frame_.curve(lambda);
  for (MonitoredHistory& mh : out_) {
    const std::vector<IntegrationPointStress>& points = s.points[mh.at.element];
    const double phi = curve.at(curve.s_from_unstrained(mh.point.x_mm)).phi_rad, w = 1.0 / points.size();
    CycleSample c;
    for (const IntegrationPointStress& ip : points) {
      const CycleSample p = local_sample(ip, phi);
      c.s11_MPa += w * p.s11_MPa, c.s22_MPa += w * p.s22_MPa, c.s12_MPa += w * p.s12_MPa, c.s33_MPa += w * p.s33_MPa;
      c.e11 += w * p.e11, c.e22 += w * p.e22, c.e12 += w * p.e12;
    }
    c.t_s = tau * frame_.period_s;
    c.s_mm = frame_.s_mm(tau);
    mh.samples.push_back(c);
  }
}

EquilibriumCheck::EquilibriumCheck(const CycleFrame& frame, Inputs inputs, CycleResult& out)
    : frame_(frame), in_(std::move(inputs)), out_(out) {}

void EquilibriumCheck::converged(double lambda, const StaticSolution& s) {
  const Mesh& m = *frame_.mesh;
  const StaticProblem& p = *in_.problem;
  const double tau = frame_.tau(lambda);
  in_.body(lambda, forces_);
  Eigen::Vector2d applied = Eigen::Vector2d::Zero(), reactions = Eigen::Vector2d::Zero(), cord = Eigen::Vector2d::Zero();
  double scale = 1e-300;  // Σ |nodal reactions| + Σ |element body forces|
  for (int e = 0; e < m.element_count(); ++e)
    applied += forces_[e] * in_.area_mm2[e], scale += (forces_[e] * in_.area_mm2[e]).norm();
  if (in_.nodal) {
    in_.nodal(lambda, nodal_);
    for (const Eigen::Vector2d& f : nodal_) applied += f, scale += f.norm();
  }
  for (const Eigen::Vector2d& f : s.inertia_N_mm) applied -= f, scale += f.norm();  // d'Alembert (PhysicsOptions::inertia)
  for (const Eigen::Vector2d& f : s.following_N_mm) applied += f, scale += f.norm();  // the flank foundation
  for (const Eigen::Vector2d& r : s.reaction_N_mm) reactions += r, scale += r.norm();
  for (int node : m.top_nodes) cord += s.reaction_N_mm[node];
  out_.equilibrium_error = std::max(out_.equilibrium_error, (reactions + applied).norm() / scale);
  out_.max_cord_reaction_N_mm = std::max(out_.max_cord_reaction_N_mm, cord.norm());
  IncrementLoads q{tau * frame_.period_s, frame_.s_mm(tau), cord, applied};
  const NeutralCurve& curve = frame_.curve(lambda);
  flank_totals(s, curve, q);
  longitudinal_loads(p, s, curve, m, *frame_.path_x, in_.integration, q);
  const belt::LoadHistory& h = *frame_.history;
  q.belt_force_N_mm = tau > 1.0 ? h.at_position(q.s_mm).F_N / in_.width_mm : 0.0;
  const double K_mid = h.at_position(q.s_mm).K_1_mm;
  q.span = tau > 1.0 && std::all_of(in_.centre_x_mm.begin(), in_.centre_x_mm.end(), [&](double x) {
    const belt::LoadState state = h.at_position(q.s_mm + x);
    return state.p_MPa == 0.0 && std::abs(state.K_1_mm - K_mid) <= 1e-6;
  });
  span_shares(q);
  out_.loads.push_back(q);
}

void EquilibriumCheck::flank_totals(const StaticSolution& s, const NeutralCurve& curve, IncrementLoads& q) const {
  for (int e = 0; !s.following_N_mm.empty() && e < frame_.mesh->element_count(); ++e) {
    const Eigen::Vector2d& flank = s.following_N_mm[e];
    if (forces_[e].isZero(0.0) && flank.isZero(0.0)) continue;
    const double phi = curve.at(curve.s_from_unstrained(in_.centre_x_mm[e])).phi_rad;
    const Eigen::Vector2d n(std::sin(phi), std::cos(phi));  // radial: the outward normal at the element's centre
    q.contact_radial_N_mm += forces_[e].dot(n) * in_.area_mm2[e];
    q.flank_radial_N_mm += flank.dot(n);
    if (!in_.along_belt) continue;
    const Eigen::Vector2d t(std::cos(phi), -std::sin(phi));
    q.contact_longitudinal_N_mm += forces_[e].dot(t) * in_.area_mm2[e];
    q.flank_longitudinal_N_mm += flank.dot(t);
  }
}

void EquilibriumCheck::span_shares(IncrementLoads& q) {
  if (!q.span || !(q.belt_force_N_mm > 0.0)) return;
  out_.span_cord_share = std::max(out_.span_cord_share, std::abs(q.cord_longitudinal_N_mm) / q.belt_force_N_mm);
  const double balance = q.left_end_longitudinal_N_mm + q.left_cord_longitudinal_N_mm + q.rubber_section_N_mm -
                         q.left_inertia_longitudinal_N_mm;
  out_.span_section_mismatch = std::max(out_.span_section_mismatch, std::abs(balance) / std::abs(q.rubber_section_N_mm));
}

FieldSnapshots::FieldSnapshots(const CycleFrame& frame, const CycleKnobs& knobs, std::vector<std::string>& files)
    : frame_(frame), knobs_(knobs), written_(knobs.outputs.vtk_at_s_mm.size(), false), files_(files) {}

void FieldSnapshots::converged(double lambda, const StaticSolution& s) {
  const double tau = frame_.tau(lambda);
  const double s_last = (tau - 1.0 - (knobs_.stepping.cycles - 1)) * frame_.history->length_mm();  // within the last cycle
  for (std::size_t k = 0; k < written_.size(); ++k) {
    if (written_[k] || s_last < knobs_.outputs.vtk_at_s_mm[k]) continue;
    VtkFields fields;
    fields.displacement_mm = s.u_mm;
    for (const auto& pts : s.points) {
      std::array<double, 4> mean{};
      for (const IntegrationPointStress& ip : pts) {
        const std::array<double, 4> v{ip.cauchy_MPa(0, 0), ip.cauchy_MPa(1, 1), ip.cauchy_MPa(0, 1), ip.sigma33_MPa};
        for (int c = 0; c < 4; ++c) mean[c] += v[c] / static_cast<double>(pts.size());
      }
      fields.cell_stress_MPa.push_back(mean);
    }
    const std::string path = knobs_.outputs.vtk_prefix + "-" + std::to_string(k) + ".vtk";
    write_vtk(*frame_.mesh, path, fields);
    files_.push_back(path);
    written_[k] = true;
  }
}

}  // namespace fitlib::segment::detail
