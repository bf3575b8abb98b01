#pragma once
// The loads on the segment (solver.hpp; docs/segment.md "Loads and solver options (reference)"):
// each an object behind one small interface, registered on StaticProblem::loads. The assembler
// (src/segment/assembler.hpp) is the one place that loops over elements, edges and nodes; a load
// says what acts there: at the integration points (integrated in the element loop), or after it
// through LoadAssembly (a dead force per element, an edge's force and tangent, a node's force and
// diagonal stiffness). The residual is internal − external (+ inertia) force, so an external load
// adds its force with a minus sign. The prescribed motion of the constrained nodes (the cord line
// on its curve) is a PrescribedMotion beside the loads.
#include <array>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "fitlib/segment/mesh.hpp"

namespace fitlib::segment {

// An element's or edge's force and tangent (up to 8 nodes; the element loop's own types).
using LoadVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 16, 1>;
using LoadMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 16, 16>;

// What a load adds after the element loop, at the current iterate and load level; implemented by
// the assembler, which turns each contribution into the nodes' local bases and the tangent's slots.
class LoadAssembly {
 public:
  virtual ~LoadAssembly() = default;
  virtual double lambda() const = 0;
  // Whether the tangent is assembled in this pass (a load may skip computing its own).
  virtual bool tangent() const = 0;
  virtual int node_count() const = 0;
  // Node a's displacement (global, mm) at the iterate, and whether it has a free component.
  virtual Eigen::Vector2d u(int node) const = 0;
  virtual bool moves(int node) const = 0;
  // Dead body forces b per element (global, N/mm³ of reference volume, uniform over the element):
  // −∫ N_a b dV into the residual, by the element loop's rule (no tangent: dead).
  virtual void add_element_forces(const std::vector<Eigen::Vector2d>& b_N_mm3) = 0;
  // Bottom edge k's residual contribution and its tangent (global components, nodes as
  // detail::edge_nodes orders them; `K` read only when tangent()).
  virtual void add_bottom_edge(int edge, LoadVector f_N_mm, LoadMatrix K_N_mm2) = 0;
  // Node a's residual contribution (global, N/mm).
  virtual void add_node_force(int node, const Eigen::Vector2d& f_N_mm) = 0;
  // k on the diagonal of node a's free equations (an isotropic stiffness: uncoupled in any basis).
  virtual void add_node_stiffness(int node, double k_N_mm2) = 0;
};

// The start of a load increment (Load::begin): its target λ, its time step, and every node's
// displacement (global, mm) where it starts: the last converged state in the increment's bases.
struct LoadStep {
  double lambda = 0.0, dt_s = 0.0;
  const std::vector<Eigen::Vector2d>* u_mm = nullptr;
};

// A converged increment (Load::commit): every node's displacement (global, mm) and every
// integration point's current position (global, mm; element by element in the rule's order).
struct ConvergedLoads {
  double lambda = 0.0;
  const std::vector<Eigen::Vector2d>* u_mm = nullptr;
  const std::vector<Eigen::Vector2d>* point_x_mm = nullptr;
  int points_per_element = 0;
};

class Load {
 public:
  virtual ~Load() = default;
  // Once per load level before its assemblies, on the calling thread (a dead load evaluates itself
  // here; a following one its frames; a committed history takes effect here).
  virtual void prepare(double /*lambda*/) {}
  // Before an increment's iterations, on the calling thread.
  virtual void begin(const LoadStep& /*step*/) {}
  // Whether at_point acts: it is then called at every integration point in the element loop.
  virtual bool acts_at_points() const { return false; }
  // At element e's integration point g (the solver's rule) and its current position x: a force
  // per reference volume b (global, N/mm³) and ∂b/∂x (N/mm⁴), false where none acts. The element
  // loop adds −∫ N_a b dV to the residual and −∫ N_a N_b ∂b/∂x dV to the tangent. Runs on any of
  // the element loop's threads: it must only read.
  virtual bool at_point(int /*element*/, int /*point*/, const Eigen::Vector2d& /*x_mm*/, Eigen::Vector2d& /*b_N_mm3*/,
                        Eigen::Matrix2d& /*db_dx_N_mm4*/) const {
    return false;
  }
  // After the element loop, on the calling thread: what it adds through `to`.
  virtual void add(LoadAssembly& /*to*/) const {}
  // After each converged increment, serially; it takes effect at the next prepare or begin, so a
  // snapshot at the converged λ still sees the increment's force.
  virtual void commit(const ConvergedLoads& /*state*/) {}
  // False when its tangent is not symmetric: the solver then takes the unsymmetric path.
  virtual bool symmetric() const { return true; }
};
using LoadPtr = std::shared_ptr<Load>;

// The loading frame's turn at a node from λ_from to λ_to (PrescribedMotion::frame_turn): its angle
// (rad, counter-clockwise) and the centre it turns about (global, mm, at λ_from).
struct FrameTurn {
  double angle_rad = 0.0;
  Eigen::Vector2d centre_mm = Eigen::Vector2d::Zero();
};

// The prescribed motion of StaticProblem::constraints: the local displacement components at λ and,
// for a line that turns with the load (the cord line, segment/static_case.hpp), its bases' angles,
// its frame's turn (the rotated predictor) and its rigid motion (the inertia's reference).
class PrescribedMotion {
 public:
  virtual ~PrescribedMotion() = default;
  // The prescribed local displacement components (mm) of every constraint at λ.
  virtual void values(double lambda, std::vector<std::array<double, 2>>& local_mm) const = 0;
  // Whether the bases, frame_turn and frame_motion below follow the load (false: fixed bases, no frame).
  virtual bool has_frame() const { return false; }
  // The constraints' basis angles at λ.
  virtual void angles(double /*lambda*/, std::vector<double>& /*angles_rad*/) const {}
  // Per node, the loading frame's turn from λ_from to λ_to (SteppingOptions::rotated_predictor).
  virtual void frame_turn(double /*from*/, double /*to*/, std::vector<FrameTurn>& /*per_node*/) const {}
  // Per node, its displacement (global, mm) at λ when carried rigidly with the loading's frame.
  virtual void frame_motion(double /*lambda*/, std::vector<Eigen::Vector2d>& /*u_mm*/) const {}
};

// Fixed-basis supports whose values a function gives (a test's or a script's).
using Prescribe = std::function<void(double lambda, std::vector<std::array<double, 2>>& local_values)>;
std::shared_ptr<const PrescribedMotion> prescribed(Prescribe values);

// The loads any problem can use; the load cycle's own are in segment/flank.hpp (the flank contact),
// src/segment/inertia.hpp (the dynamics' m·a) and src/segment/cycle_parts.hpp (what the body and
// nodal forces below are given there: Report I's 6.6–6.9, the end faces' shear).

// Dead body forces per element at λ (global, N/mm³ of reference volume, uniform over each
// element; zero where none), as consistent nodal loads f_a = ∫ N_a b dV (body_force.cpp).
using ElementForcesAt = std::function<void(double lambda, std::vector<Eigen::Vector2d>& b_N_mm3)>;
LoadPtr dead_body_force(int elements, ElementForcesAt b);

// Dead nodal forces at λ (global, N per mm of width, per node; zero where none; nodal_force.cpp).
using NodeForcesAt = std::function<void(double lambda, std::vector<Eigen::Vector2d>& f_N_mm)>;
LoadPtr dead_nodal_force(NodeForcesAt f);

// The follower pressure λ p on the mesh's bottom edges, normal to the current edge, with its
// (unsymmetric) tangent (follower_pressure.cpp; element.hpp's pressure_load).
class FollowerPressure final : public Load {
 public:
  FollowerPressure(const Mesh& mesh, double pressure_MPa) : mesh_(mesh), pressure_MPa_(pressure_MPa) {}
  double pressure_MPa() const { return pressure_MPa_; }
  void add(LoadAssembly& to) const override;
  bool symmetric() const override { return pressure_MPa_ == 0.0; }

 private:
  const Mesh& mesh_;
  double pressure_MPa_;
};

}  // namespace fitlib::segment
