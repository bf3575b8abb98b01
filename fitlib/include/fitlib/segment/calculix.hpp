#pragma once
// The segment's own mesh and load case as a CalculiX input deck, for the independent-oracle
// comparison (issue 11 item 6): plane strain CPE8R, NLGEOM, *ELASTIC (St Venant–Kirchhoff under
// NLGEOM), the prescribed cord-line displacements and radial end lines (*TRANSFORM) at full load,
// follower pressure on the bottom faces (*DLOAD P1), integration-point stresses in the .dat file.
// Numbers are written with 13 significant digits (CalculiX reads at most 20 characters a field).
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fitlib/segment/solver.hpp"
#include "fitlib/segment/static_case.hpp"

namespace fitlib::segment {

// `law`: St Venant–Kirchhoff (*ELASTIC) or neo-Hookean (*HYPERELASTIC, NEO HOOKE with C10 = μ/2,
// D1 = 2/K: the same small-strain moduli as make_elastic's neo-Hookean, the same law when J = 1).
std::string calculix_deck(const StaticProblem& problem, const std::array<IsotropicElastic, 2>& materials,
                          int increments, ElasticLaw law = ElasticLaw::st_venant_kirchhoff);

// Integration-point Cauchy stresses from a CalculiX .dat (*EL PRINT S), per element, in the
// 2 × 2 order of the segment solver (ξ fastest); the solution's other fields stay empty.
StaticSolution read_calculix_stresses(const std::string& dat_text, const Mesh& mesh);

}  // namespace fitlib::segment
