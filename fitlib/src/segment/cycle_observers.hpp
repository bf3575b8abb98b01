#pragma once
// The observers of a load-cycle run (cycle.cpp), each called after every converged increment:
// the monitored points' stress and strain histories, the equilibrium check and the increment's
// load totals, the full-field VTK snapshots, and progress.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cycle_parts.hpp"
#include "fitlib/segment/cycle.hpp"
#include "fitlib/segment/observer.hpp"

namespace fitlib::segment::detail {

// What the observers read of a run: the moulded reference mesh, each node's unstrained path
// position, the history, the pseudo time's scale T (λ τ = T) and the cycle's period.
struct CycleFrame {
  const Mesh* mesh = nullptr;
  const std::vector<double>* path_x = nullptr;
  const belt::LoadHistory* history = nullptr;
  double T = 1.0, period_s = 0.0;
  CurveAt curve_at;
  double tau(double lambda) const { return lambda * T; }
  // The segment's middle's path position at λ (0 in the bending step).
  double s_mm(double tau) const { return std::max(0.0, tau - 1.0) * history->length_mm(); }
  // The cord curve at λ, built once per increment for every observer that reads it.
  const NeutralCurve& curve(double lambda) const {
    if (!curve_ || lambda != curve_lambda_) curve_.emplace(curve_at(lambda)), curve_lambda_ = lambda;
    return *curve_;
  }
  mutable std::optional<NeutralCurve> curve_;  // curve()'s cache
  mutable double curve_lambda_ = 0.0;
};

// The named points' stresses (local frame of the cord curve) and logarithmic strains, interpolated
// from their elements' integration points as `stress_at` does (segment/solver.hpp).
class PointMonitor : public IncrementObserver {
 public:
  // `straight`: the mesh before wrapping on the mould (curvature K_m); the points are given there.
  PointMonitor(const CycleFrame& frame, const Mesh& straight, double K_m, const std::vector<NamedPoint>& named,
               int gauss_order, std::vector<MonitoredHistory>& out);
  void converged(double lambda, const StaticSolution& s) override;

 private:
  const CycleFrame& frame_;
  int order_;
  std::vector<MonitoredHistory>& out_;
  std::vector<Eigen::Vector2d> surface_tangent_;  // per history: the moulded surface's (zero off the surface)
};

// The design regions' points (CycleOutputs::scan_design_regions): every integration point of the
// bottom rubber between the central cogs, the gap's surface nodes, and the cushion's mid-depth below
// each element centre of the central section; each point's stresses and strains in the cord
// curve's local frame at its unstrained path position (an integration point's own, the others
// interpolated as a named point's).
class RegionScan : public IncrementObserver {
 public:
  // `straight`: the mesh before wrapping on the mould (curvature K_m).
  RegionScan(const CycleFrame& frame, const Mesh& straight, double K_m, const CogSection& section,
             const MeshKnobs& knobs, int gauss_order, std::vector<MonitoredHistory>& out);
  void converged(double lambda, const StaticSolution& s) override;

 private:
  void add_bottom_points(const Mesh& straight, const CogSection& section);
  void add_surface_nodes(const Mesh& straight, const CogSection& section);
  void add_cushion_points(const Mesh& straight, double K_m, const CogSection& section, const MeshKnobs& knobs);

  const CycleFrame& frame_;
  int order_;
  std::vector<MonitoredHistory>& out_;
  std::vector<Eigen::Vector2d> surface_tangent_;  // per history: the moulded surface's (zero off the surface)
};

// Each element's mean over its integration points (CycleOutputs::record_elements): stresses and
// logarithmic strains in the cord curve's local frame at the element centre's unstrained path position.
class ElementMeans : public IncrementObserver {
 public:
  // `straight`: the mesh before wrapping on the mould (the centres' path positions).
  ElementMeans(const CycleFrame& frame, const Mesh& straight, std::vector<MonitoredHistory>& out);
  void converged(double lambda, const StaticSolution& s) override;

 private:
  const CycleFrame& frame_;
  std::vector<MonitoredHistory>& out_;
};

// A point's stresses in the cord curve's local frame at angle φ (1 radial, 2 along the belt) and
// its logarithmic strain in the same frame.
CycleSample local_sample(const IntegrationPointStress& ip, double phi);

// The built-in equilibrium check, Σ reactions + ∫ b dV = 0 (the free residual is at the tolerance),
// and each increment's load totals (CycleResult::loads, span shares; docs/segment.md "Cord-line
// reactions and the belt force").
class EquilibriumCheck : public IncrementObserver {
 public:
  struct Inputs {
    const StaticProblem* problem = nullptr;  // its section force
    LoadAt body;                             // the contact body forces per element
    LoadAt nodal;                            // the end faces' nodal forces (empty: none)
    std::vector<double> area_mm2;            // per element, reference
    std::vector<double> centre_x_mm;         // per element, unstrained path position
    bool along_belt = false;                 // a tangential flank law (its longitudinal totals)
    double width_mm = 0.0;
    Integration integration = Integration::reduced;
  };
  EquilibriumCheck(const CycleFrame& frame, Inputs inputs, CycleResult& out);
  void converged(double lambda, const StaticSolution& s) override;

 private:
  // The radial and (with a tangential flank) longitudinal totals of the dead contact load and the flank's.
  void flank_totals(const StaticSolution& s, const NeutralCurve& curve, IncrementLoads& q) const;
  // The span's cord share and the left half's balance (CycleResult::span_cord_share, span_section_mismatch).
  void span_shares(IncrementLoads& q);

  const CycleFrame& frame_;
  Inputs in_;
  CycleResult& out_;
  std::vector<Eigen::Vector2d> forces_, nodal_;
};

// Full-field stress (VTK, cell means) when the segment's middle first reaches each path position
// of the last cycle (CycleOutputs::vtk_at_s_mm, vtk_prefix; CycleStepping::cycles).
class FieldSnapshots : public IncrementObserver {
 public:
  FieldSnapshots(const CycleFrame& frame, const CycleKnobs& knobs, std::vector<std::string>& files);
  void converged(double lambda, const StaticSolution& s) override;

 private:
  const CycleFrame& frame_;
  const CycleKnobs& knobs_;
  std::vector<bool> written_;
  std::vector<std::string>& files_;
};

// The share of the run done (CycleOutputs::progress) and the last converged λ (a failure's message).
class ProgressReport : public IncrementObserver {
 public:
  explicit ProgressReport(std::function<void(double done)> report) : report_(std::move(report)) {}
  void converged(double lambda, const StaticSolution&) override {
    last_lambda_ = lambda;
    if (report_) report_(lambda);
  }
  double last_lambda() const { return last_lambda_; }

 private:
  std::function<void(double)> report_;
  double last_lambda_ = 0.0;
};

}  // namespace fitlib::segment::detail
