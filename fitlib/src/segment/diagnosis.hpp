#pragma once
// Diagnosis of a failed Newton increment (SolverKnobs::diagnose_failure; docs/segment.md §Solver,
// "Failure diagnosis"): the tangent against central differences of the residual (assembled, per
// element, per integration point, with a one-sided kink measure), the lowest eigenvalues of the
// tangent's symmetric part and the residual along Newton's direction. The solver hands over its
// assembly at one load level and step as callbacks, so the checks see exactly what Newton saw.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "element.hpp"
#include "fitlib/segment/mesh.hpp"

namespace fitlib::segment::detail {

struct DiagnosisProblem {
  const Mesh* mesh = nullptr;
  const std::vector<int>* eq = nullptr;               // per dof (2 per node): equation, or −1 when prescribed
  const std::vector<Eigen::Matrix2d>* basis = nullptr;  // per node: columns = its local basis
  // Residual of all dofs (local components) at q, or an empty vector when an element inverts.
  std::function<Eigen::VectorXd(const Eigen::VectorXd& q)> residual;
  // The free-free tangent at q.
  std::function<Eigen::SparseMatrix<double>(const Eigen::VectorXd& q)> tangent;
  // One element's internal force (global components) and, if asked, tangent and point states at q.
  std::function<bool(const Eigen::VectorXd& q, int element, ElementVector& f, ElementMatrix* K,
                     std::vector<ElementState>* states)>
      element;
  // One integration point's response to F on the step's committed state.
  std::function<PointResponse(int element, int point, const Eigen::Matrix2d& F, bool tangent)> point;
};

// The findings at the iterate q, one paragraph headed by `label`.
std::string diagnose(const DiagnosisProblem& problem, const Eigen::VectorXd& q, const std::string& label);

}  // namespace fitlib::segment::detail
