// The prescribed motions of the constrained nodes (fitlib/segment/load.hpp): fixed supports whose
// values a function gives, and the cord line placed on a curve that changes with λ
// (segment/static_case.hpp's cord_curve_problem; Report I §5: the cord-line nodes on the curve of
// curvature K and strain ε at their unstrained path position, the end faces on the curve's normal
// through its end point; docs/segment.md "Loading by the load cycle").
#include "fitlib/segment/load.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Geometry>

#include "fitlib/segment/static_case.hpp"

namespace fitlib::segment {
namespace {

class FunctionMotion final : public PrescribedMotion {
 public:
  explicit FunctionMotion(Prescribe values) : values_(std::move(values)) {}
  void values(double lambda, std::vector<std::array<double, 2>>& v) const override { values_(lambda, v); }

 private:
  Prescribe values_;
};

// The mesh's columns: the distinct unstrained path positions and each node's column. A column's
// nodes share one cord frame, so the frames are computed once per column.
struct Columns {
  std::vector<double> x_mm;
  std::vector<int> of_node;
};

Columns columns_of(const std::vector<double>& path_x_mm) {
  Columns c{path_x_mm, {}};
  std::sort(c.x_mm.begin(), c.x_mm.end());
  c.x_mm.erase(std::unique(c.x_mm.begin(), c.x_mm.end()), c.x_mm.end());
  for (double x : path_x_mm)
    c.of_node.push_back(static_cast<int>(std::lower_bound(c.x_mm.begin(), c.x_mm.end(), x) - c.x_mm.begin()));
  return c;
}

// The cord curve's point and tangent angle at each column.
std::vector<CurvePoint> column_frames(const NeutralCurve& curve, const Columns& columns) {
  std::vector<CurvePoint> at;
  for (double x : columns.x_mm) at.push_back(curve.at(curve.s_from_unstrained(x)));
  return at;
}

// The cord line on the curve at λ: the top nodes on it, the end-face nodes (constraints n_top …)
// on its normal through their column's cord point, shifted along the tangent by `end_shift`.
class CordLine final : public PrescribedMotion {
 public:
  CordLine(const Mesh& m, std::vector<NodeConstraint> constraints, std::size_t n_top, std::vector<double> path_x_mm,
           std::function<NeutralCurve(double)> curve_at, EndShift end_shift)
      : mesh_(m), constraints_(std::move(constraints)), n_top_(n_top), path_x_(std::move(path_x_mm)),
        curve_at_(std::move(curve_at)), end_shift_(std::move(end_shift)), columns_(columns_of(path_x_)),
        reference_(column_frames(curve_at_(0.0), columns_)) {}

  void values(double lambda, std::vector<std::array<double, 2>>& v) const override {
    const NeutralCurve curve = curve_at_(lambda);
    for (std::size_t c = 0; c < constraints_.size(); ++c) {
      const int node = constraints_[c].node;
      const Eigen::Vector2d& X = mesh_.X[node];
      const CurvePoint q = curve.at(curve.s_from_unstrained(path_x_[node]));
      if (c < n_top_) {
        v[c] = {q.x_mm - X.x(), q.y_mm - X.y()};
      } else {  // stay on the radial line through the cord point: (x − q)·t = 0
        const Eigen::Vector2d t(std::cos(q.phi_rad), -std::sin(q.phi_rad));
        const Eigen::Vector2d r = Eigen::Vector2d(q.x_mm, q.y_mm) - X;
        v[c] = {r.dot(t) + (end_shift_ ? end_shift_(node, lambda) : 0.0), 0.0};
      }
    }
  }
  bool has_frame() const override { return true; }
  // The end faces' bases turn with the curve's normal at their column (e0 = tangent).
  void angles(double lambda, std::vector<double>& angles) const override {
    const NeutralCurve curve = curve_at_(lambda);
    for (std::size_t c = n_top_; c < angles.size(); ++c)
      angles[c] = -curve.at(curve.s_from_unstrained(path_x_[constraints_[c].node])).phi_rad;
  }
  // Each node turns with the cord's frame at its unstrained path position, as a plane section of a
  // beam does.
  void frame_turn(double from, double to, std::vector<FrameTurn>& turns) const override {
    const std::vector<CurvePoint> a = column_frames(curve_at_(from), columns_), b = column_frames(curve_at_(to), columns_);
    turns.resize(columns_.of_node.size());
    for (std::size_t n = 0; n < turns.size(); ++n) {
      const CurvePoint &pa = a[columns_.of_node[n]], &pb = b[columns_.of_node[n]];
      turns[n] = {pa.phi_rad - pb.phi_rad, {pa.x_mm, pa.y_mm}};  // φ turns clockwise
    }
  }
  // Each node carried rigidly with its column's cord frame from the reference (λ = 0): the motion the
  // segment's inertia is measured against (PhysicsOptions::inertia; docs/segment.md "Inertia").
  void frame_motion(double lambda, std::vector<Eigen::Vector2d>& u) const override {
    const std::vector<CurvePoint> now = column_frames(curve_at_(lambda), columns_);
    u.resize(columns_.of_node.size());
    for (std::size_t n = 0; n < u.size(); ++n) {
      const CurvePoint &c = now[columns_.of_node[n]], &c0 = reference_[columns_.of_node[n]];
      const double th = c0.phi_rad - c.phi_rad;  // φ turns clockwise
      const Eigen::Vector2d r = mesh_.X[n] - Eigen::Vector2d(c0.x_mm, c0.y_mm);
      const Eigen::Vector2d x = Eigen::Vector2d(c.x_mm, c.y_mm) + Eigen::Rotation2Dd(th).toRotationMatrix() * r;
      u[n] = x - mesh_.X[n];
    }
  }

 private:
  const Mesh& mesh_;
  std::vector<NodeConstraint> constraints_;
  std::size_t n_top_;
  std::vector<double> path_x_;
  std::function<NeutralCurve(double)> curve_at_;
  EndShift end_shift_;
  Columns columns_;
  std::vector<CurvePoint> reference_;  // the columns' frames at λ = 0
};

}  // namespace

std::shared_ptr<const PrescribedMotion> prescribed(Prescribe values) {
  return std::make_shared<FunctionMotion>(std::move(values));
}

std::shared_ptr<const PrescribedMotion> cord_line(const Mesh& m, std::vector<NodeConstraint> constraints,
                                                  std::size_t n_top, std::vector<double> path_x_mm,
                                                  std::function<NeutralCurve(double lambda)> curve_at,
                                                  EndShift end_shift_mm) {
  return std::make_shared<CordLine>(m, std::move(constraints), n_top, std::move(path_x_mm), std::move(curve_at),
                                    std::move(end_shift_mm));
}

}  // namespace fitlib::segment
