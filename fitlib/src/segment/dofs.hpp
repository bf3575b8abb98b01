#pragma once
// The segment solver's unknowns and the tangent's sparsity (solver.cpp): two local components per
// node, a constrained node's basis rotated so a prescribed component is one unknown; the free-free
// tangent's pattern built once per run, with each element's and bottom edge's slots into it.
#include <vector>

#include <Eigen/Core>

#include "linear_solver.hpp"
#include "fitlib/segment/solver.hpp"

namespace fitlib::segment::detail {

// Global unknowns: two local components per node; a constrained node's basis is rotated.
struct Dofs {
  std::vector<Eigen::Matrix2d> R;  // columns = local basis vectors
  std::vector<int> eq;             // 2 per node: equation number, or −1 when prescribed
  std::vector<int> constraint;     // per node: index in the problem's constraints, or −1
  int equations = 0;
};
Dofs number_dofs(const StaticProblem& problem);

// All integration points' states in one contiguous block: element e's points start at offset[e].
struct StateBlock {
  std::vector<std::size_t> offset;
  std::vector<double> committed, trial;
};
StateBlock initial_states(const StaticProblem& problem, std::size_t points_per_element);

// The free-free tangent's sparsity, built once: per element and per bottom edge, the position in
// K's value array of each local (row dof, column dof) pair, or −1 when either is prescribed.
struct Pattern {
  SparseMatrix K;
  std::vector<std::vector<int>> element_slots, edge_slots;
};
Pattern build_pattern(const Mesh& mesh, const Dofs& dofs);
// The pattern with the free equations renumbered in the node groups' AMD order (grouped_ldlt.hpp),
// the elimination order of the symmetric solver.
Pattern ordered_pattern(const Mesh& mesh, Dofs& dofs);
// Per equation: the slot of K_ii in K's values.
std::vector<int> diagonal_slots(const SparseMatrix& K);

// An edge's nodes (2 or 3).
std::vector<int> edge_nodes(const Edge& edge);
// The Euclidean norm of r's free (`free`) or prescribed components.
double free_norm(const Eigen::VectorXd& r, const Dofs& dofs, bool free);

}  // namespace fitlib::segment::detail
