#pragma once
// Private to the fit module: variable projection for series models (docs/fitting.md "Free time
// constants by variable projection").
#include "backends.hpp"

namespace fitlib::fit::detail {

// Variable projection (Golub & Pereyra 1973, with Kaufman's 1975 Jacobian) over the problem's
// free set: the linear parameters (term moduli, relaxed modulus) re-solved by NNLS at every trial
// point, the others (time constants, law constants) moved by Levenberg–Marquardt on the Jacobian
// projected off the active linear columns, within their bounds. Exact for relative and absolute
// residuals (the NNLS design is then the objective); with log10 residuals the NNLS solves the
// first-order form, and the point is a start for Ceres. Keeps the lowest cost seen.
StageOutcome run_varpro(Problem& problem, int max_iterations);

}  // namespace fitlib::fit::detail
