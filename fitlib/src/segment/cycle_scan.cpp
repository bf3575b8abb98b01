// The design regions' scan of a load-cycle run (cycle_observers.hpp, RegionScan; Report I §6.4).
#include <algorithm>
#include <cmath>
#include <string>

#include "cycle_observers.hpp"
#include "cycle_parts.hpp"
#include "element.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib::segment::detail {
namespace {

double centroid_x(const Mesh& straight, int e) {
  double x = 0.0;
  for (int a = 0; a < 4; ++a) x += 0.25 * straight.X[straight.elements[e][a]].x();
  return x;
}

// Report I monitors the elements between the cogs and every cushion element (L1020–1030): here the
// bottom rubber over the gap's land and root fillets, where a radial crack starts.
double gap_half_width_mm(const CogSection& section) { return section.land_half_width_mm + section.root_fillet_mm; }

}  // namespace

RegionScan::RegionScan(const CycleFrame& frame, const Mesh& straight, double K_m, const CogSection& section,
                       const MeshKnobs& knobs, int gauss_order, std::vector<MonitoredHistory>& out)
    : frame_(frame), order_(gauss_order), out_(out) {
  add_bottom_points(straight, section);
  add_surface_nodes(straight, section);
  add_cushion_points(straight, K_m, section, knobs);
  surface_tangent_.resize(out_.size(), Eigen::Vector2d::Zero());
}

void RegionScan::add_bottom_points(const Mesh& straight, const CogSection& section) {
  const std::vector<GaussPoint> rule = gauss_rule(order_);
  const int nodes = straight.nodes_per_element;
  double N[8], dxi[8], deta[8];
  for (int e = 0; e < straight.element_count(); ++e) {
    if (straight.roles[e] != Role::bottom || std::abs(centroid_x(straight, e)) > gap_half_width_mm(section)) continue;
    for (std::size_t g = 0; g < rule.size(); ++g) {
      shape(nodes, rule[g].xi, rule[g].eta, N, dxi, deta);
      Eigen::Vector2d X = Eigen::Vector2d::Zero();  // on the straight mesh: the path position's frame
      for (int a = 0; a < nodes; ++a) X += N[a] * straight.X[straight.elements[e][a]];
      MonitoredHistory mh;
      mh.point = {"e" + std::to_string(e) + "-ip" + std::to_string(g), X.x(), X.y()};
      mh.role = Role::bottom;
      mh.at.element = e, mh.at.xi = {rule[g].xi, rule[g].eta};
      mh.gauss_point = static_cast<int>(g);
      out_.push_back(std::move(mh));
    }
  }
}

// The gap's surface, where a radial crack starts: its nodes' stresses interpolated as a named
// point's (the integration points lie inside the elements, below the surface's peak), then made
// traction-free: the extrapolation to a surface node of a graded mesh leaves σ_nn and σ_nt of up
// to 0.8 MPa on the flat land (medium drive), where the surface carries none.
void RegionScan::add_surface_nodes(const Mesh& straight, const CogSection& section) {
  std::vector<int> surface;
  for (const Edge& edge : straight.bottom_edges)
    for (int node : edge.nodes)
      if (node >= 0 && std::abs(straight.X[node].x()) <= gap_half_width_mm(section) &&
          std::find(surface.begin(), surface.end(), node) == surface.end())
        surface.push_back(node);
  std::sort(surface.begin(), surface.end(), [&straight](int a, int b) { return straight.X[a].x() < straight.X[b].x(); });
  const Mesh& moulded = *frame_.mesh;
  for (std::size_t k = 0; k < surface.size(); ++k) {
    const int node = surface[k];
    // The moulded surface's tangent, from the neighbouring surface nodes (one-sided at the ends).
    const int before = surface[k == 0 ? 0 : k - 1], after = surface[std::min(k + 1, surface.size() - 1)];
    surface_tangent_.resize(out_.size(), Eigen::Vector2d::Zero());  // zero: not a surface point
    surface_tangent_.push_back((moulded.X[after] - moulded.X[before]).normalized());
    MonitoredHistory mh;
    mh.point = {"surface-n" + std::to_string(node), straight.X[node].x(), straight.X[node].y()};
    mh.X_mm = moulded.X[node];
    mh.at = locate(moulded, mh.X_mm);
    mh.role = Role::bottom;
    out_.push_back(std::move(mh));
  }
}

// The cushion at its mid-depth, where the named mid-cushion point reads separation (docs/segment.md
// "Mode 2 through the cushion"), below each cushion element's centre over the fine central section
// (the coarse end sections carry the short segment's end effect). Not at its integration points: on
// the one-row cushion the row next to the prescribed cord line peaks spuriously at a pulley's exit
// (the light drive's complete level: σ11 1.40 MPa at 0.11 mm depth against −0.55 at mid-depth).
void RegionScan::add_cushion_points(const Mesh& straight, double K_m, const CogSection& section, const MeshKnobs& knobs) {
  Mesh points = straight;  // carried into the moulded reference as the nodes are (PointMonitor)
  points.X.clear();
  for (int e = 0; e < straight.element_count(); ++e) {
    const double x = centroid_x(straight, e);
    if (straight.roles[e] == Role::cushion && std::abs(x) <= 0.5 * knobs.central_pitches * section.cog_pitch_mm)
      points.X.emplace_back(x, -0.5 * section.cushion_mm);
  }
  std::sort(points.X.begin(), points.X.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() < b.x(); });
  points.X.erase(std::unique(points.X.begin(), points.X.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
                   return std::abs(a.x() - b.x()) < 1e-9;
                 }), points.X.end());  // one per column, however many cushion rows
  const Mesh moulded = wrapped(points, K_m);
  for (std::size_t k = 0; k < points.X.size(); ++k) {
    MonitoredHistory mh;
    mh.point = {"cushion-x" + core::format_number(points.X[k].x(), 4), points.X[k].x(), points.X[k].y()};
    mh.X_mm = moulded.X[k];
    mh.at = locate(*frame_.mesh, mh.X_mm);
    mh.role = Role::cushion;
    out_.push_back(std::move(mh));
  }
}

void RegionScan::converged(double lambda, const StaticSolution& s) {
  const double tau = frame_.tau(lambda);
  const NeutralCurve& curve = frame_.curve(lambda);
  for (MonitoredHistory& mh : out_) {
    IntegrationPointStress ip;
    if (mh.gauss_point >= 0) {
      ip = s.points[mh.at.element][mh.gauss_point];
    } else {
      ip = interpolate(s, mh.at, order_, mh.X_mm);
      const Eigen::Vector2d& T = surface_tangent_[&mh - out_.data()];
      if (T.squaredNorm() > 0.0) {  // a free surface carries σ_tt alone: drop what the extrapolation leaves
        const Eigen::Vector2d t = (ip.F * T).normalized();
        ip.cauchy_MPa = t.dot(ip.cauchy_MPa * t) * t * t.transpose();
      }
    }
    CycleSample c = local_sample(ip, curve.at(curve.s_from_unstrained(mh.point.x_mm)).phi_rad);
    c.t_s = tau * frame_.period_s;
    c.s_mm = frame_.s_mm(tau);
    mh.samples.push_back(c);
  }
}

}  // namespace fitlib::segment::detail
